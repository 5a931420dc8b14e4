#include <cmath>

#include "pipeline/kernels.h"

namespace dv {

ChromaTransform ChromaTransform::of(ColorSpace space) {
  ChromaTransform t{};
  if (space == ColorSpace::YUV) {
    // BT.601 U and V.
    t = {{-0.14713f, -0.28886f, 0.436f}, {0.615f, -0.51499f, -0.10001f}};
  } else {
    // 1.5 x orthonormal basis of the plane normal to gray: (1,-1,0)/sqrt2 and
    // (1,1,-2)/sqrt6. Dot products equal those of the three dRGB channels.
    const float s2 = 1.5f / std::sqrt(2.0f), s6 = 1.5f / std::sqrt(6.0f);
    t = {{s2, -s2, 0}, {s6, s6, -2 * s6}};
  }
  return t;
}

__attribute__((target_clones("avx2", "default"))) void rectifyChromaRows(
    const RemapTable& table, const uint32_t* src, float gain, float* ca, float* cb, int y_begin,
    int y_end) {
  const int w = table.width;
  const int stride = table.src_width;
  const float k = 1.0f / 256.0f;
  for (int y = y_begin; y < y_end; ++y) {
    const size_t row = static_cast<size_t>(y) * w;
    const int32_t* idx = table.index.data() + row;
    const uint16_t* fr = table.frac.data() + row;
    float* oa = ca + row;
    float* ob = cb + row;
    for (int x = 0; x < w; ++x) {
      const int i = idx[x];
      const uint32_t p00 = src[i], p01 = src[i + 1], p10 = src[i + stride],
                     p11 = src[i + stride + 1];
      const float fx = (fr[x] & 255) * k, fy = (fr[x] >> 8) * k;
      const float w11 = fx * fy, w01 = fx - w11, w10 = fy - w11, w00 = 1 - fx - fy + w11;
      // Low half a, high half b, both int16.
      auto lo = [](uint32_t p) { return static_cast<float>(static_cast<int16_t>(p & 0xffffu)); };
      auto hi = [](uint32_t p) { return static_cast<float>(static_cast<int32_t>(p) >> 16); };
      oa[x] = (w00 * lo(p00) + w01 * lo(p01) + w10 * lo(p10) + w11 * lo(p11)) * gain;
      ob[x] = (w00 * hi(p00) + w01 * hi(p01) + w10 * hi(p10) + w11 * hi(p11)) * gain;
    }
  }
}

}  // namespace dv

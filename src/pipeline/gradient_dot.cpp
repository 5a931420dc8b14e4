#include <cmath>
#include <cstring>

#include "pipeline/kernels.h"

namespace dv {

__attribute__((target_clones("avx2", "default"))) void gradientDotRows(
    const float* ca, const float* cb, int width, int height, double scale, int32_t* g, int y_begin,
    int y_end) {
  // i(x + s) with s = k + a: linear between samples k and k + 1 away.
  const int k = static_cast<int>(std::floor(scale));
  const float a = static_cast<float>(scale - k), na = 1 - a;
  const int m = k + 1;  // reach of the gradient
  for (int y = y_begin; y < y_end; ++y) {
    int32_t* out = g + static_cast<size_t>(y) * width;
    if (y < m || y >= height - m || width <= 2 * m) {
      std::memset(out, 0, sizeof(int32_t) * width);
      continue;
    }
    for (int x = 0; x < m; ++x) out[x] = 0, out[width - 1 - x] = 0;
    const size_t w = width;
    const float* a_rows[4] = {ca + (y - k - 1) * w, ca + (y - k) * w, ca + (y + k) * w,
                              ca + (y + k + 1) * w};
    const float* b_rows[4] = {cb + (y - k - 1) * w, cb + (y - k) * w, cb + (y + k) * w,
                              cb + (y + k + 1) * w};
    const float* a_mid = ca + y * w;
    const float* b_mid = cb + y * w;
    for (int x = m; x < width - m; ++x) {
      const float gxa = na * (a_mid[x + k] - a_mid[x - k]) + a * (a_mid[x + k + 1] - a_mid[x - k - 1]);
      const float gya = na * (a_rows[2][x] - a_rows[1][x]) + a * (a_rows[3][x] - a_rows[0][x]);
      const float gxb = na * (b_mid[x + k] - b_mid[x - k]) + a * (b_mid[x + k + 1] - b_mid[x - k - 1]);
      const float gyb = na * (b_rows[2][x] - b_rows[1][x]) + a * (b_rows[3][x] - b_rows[0][x]);
      // Truncation (not lrintf, which the compiler will not vectorise);
      // its bias toward zero is symmetric for both signs.
      out[x] = static_cast<int32_t>((gxa * gya + gxb * gyb) * kGradientFixedPoint);
    }
  }
}

float windowGradientEnergy(const float* ca, const float* cb, int width, double scale, int x, int y,
                           int r) {
  const int k = static_cast<int>(std::floor(scale));
  const float a = static_cast<float>(scale - k), na = 1 - a;
  const size_t w = width;
  double sum = 0;
  for (int yy = y - r; yy <= y + r; ++yy) {
    for (int xx = x - r; xx <= x + r; ++xx) {
      for (const float* c : {ca, cb}) {
        const float* mid = c + yy * w;
        const float gx = na * (mid[xx + k] - mid[xx - k]) + a * (mid[xx + k + 1] - mid[xx - k - 1]);
        const float gy = na * (c[(yy + k) * w + xx] - c[(yy - k) * w + xx]) +
                         a * (c[(yy + k + 1) * w + xx] - c[(yy - k - 1) * w + xx]);
        sum += 0.5 * (gx * gx + gy * gy);
      }
    }
  }
  return static_cast<float>(sum / ((2 * r + 1) * (2 * r + 1)));
}

}  // namespace dv

#include <cmath>
#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

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

namespace {

// Bilinear interpolation in integers: weights in 1/256, first along x, then
// along y, so the sum is exact (|packed| < 2^15 gives |result| < 2^31) and
// every code path (and the OpenCL kernel) gets the same value.
inline int32_t lerp2(int32_t v00, int32_t v01, int32_t v10, int32_t v11, int32_t fx, int32_t fy) {
  const int32_t top = v00 * (256 - fx) + v01 * fx;
  const int32_t bot = v10 * (256 - fx) + v11 * fx;
  return top * (256 - fy) + bot * fy;
}

void rectifyScalar(const int32_t* idx, const uint16_t* fr, int stride, const uint32_t* src, float scale,
                   float* ca, float* cb, size_t begin, size_t end) {
  auto lo = [](uint32_t p) { return static_cast<int32_t>(static_cast<int16_t>(p & 0xffffu)); };
  auto hi = [](uint32_t p) { return static_cast<int32_t>(p) >> 16; };
  for (size_t k = begin; k < end; ++k) {
    const int i = idx[k];
    const uint32_t p00 = src[i], p01 = src[i + 1], p10 = src[i + stride], p11 = src[i + stride + 1];
    const int32_t fx = fr[k] & 255, fy = fr[k] >> 8;
    ca[k] = static_cast<float>(lerp2(lo(p00), lo(p01), lo(p10), lo(p11), fx, fy)) * scale;
    cb[k] = static_cast<float>(lerp2(hi(p00), hi(p01), hi(p10), hi(p11), fx, fy)) * scale;
  }
}

#if defined(__x86_64__)
// The two horizontal neighbours of a sample (a00 b00 a01 b01) in one load.
inline long long pairAt(const uint32_t* p) {
  long long v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Four cells k..k+3: a byte shuffle pairs each row's neighbours as
// (a00 a01)(b00 b01), pmaddwd applies the x weights, then two 32-bit
// products the y weights. Lanes of the result: a0 b0 a1 b1 a2 b2 a3 b3.
// (Scalar loads: AVX2 gathers are slower here.)
__attribute__((target("avx2"))) inline __m256i lerp4(const uint32_t* top, const uint32_t* bot,
                                                     const int32_t* idx, __m128i frac16) {
  const __m256i pair = _mm256_setr_epi8(0, 1, 4, 5, 2, 3, 6, 7, 8, 9, 12, 13, 10, 11, 14, 15,  //
                                        0, 1, 4, 5, 2, 3, 6, 7, 8, 9, 12, 13, 10, 11, 14, 15);
  const int i0 = idx[0], i1 = idx[1], i2 = idx[2], i3 = idx[3];
  const __m256i t = _mm256_shuffle_epi8(
      _mm256_setr_epi64x(pairAt(top + i0), pairAt(top + i1), pairAt(top + i2), pairAt(top + i3)), pair);
  const __m256i b = _mm256_shuffle_epi8(
      _mm256_setr_epi64x(pairAt(bot + i0), pairAt(bot + i1), pairAt(bot + i2), pairAt(bot + i3)), pair);
  const __m256i f = _mm256_cvtepu16_epi64(frac16);  // one frac per 64-bit lane
  const __m256i fx = _mm256_and_si256(f, _mm256_set1_epi64x(255));
  const __m256i fy = _mm256_srli_epi64(f, 8);
  // x weights (256 - fx, fx) in both 32-bit halves; fy in both halves.
  const __m256i wx1 = _mm256_or_si256(_mm256_sub_epi64(_mm256_set1_epi64x(256), fx), _mm256_slli_epi64(fx, 16));
  const __m256i wx = _mm256_or_si256(wx1, _mm256_slli_epi64(wx1, 32));
  const __m256i wy = _mm256_or_si256(fy, _mm256_slli_epi64(fy, 32));
  const __m256i top_v = _mm256_madd_epi16(t, wx);
  const __m256i bot_v = _mm256_madd_epi16(b, wx);
  return _mm256_add_epi32(_mm256_mullo_epi32(top_v, _mm256_sub_epi32(_mm256_set1_epi32(256), wy)),
                          _mm256_mullo_epi32(bot_v, wy));
}

__attribute__((target("avx2"))) void rectifyAvx2(const int32_t* idx, const uint16_t* fr, int stride,
                                                 const uint32_t* src, float scale, float* ca, float* cb,
                                                 size_t begin, size_t end) {
  const uint32_t* bot = src + stride;
  const __m256 s = _mm256_set1_ps(scale);
  // a0 a1 a2 a3 | b0 b1 b2 b3 within one 4-cell result.
  const __m256i split = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  size_t k = begin;
  for (; k + 8 <= end; k += 8) {
    const __m128i f = _mm_loadu_si128(reinterpret_cast<const __m128i*>(fr + k));
    const __m256i r0 = _mm256_permutevar8x32_epi32(lerp4(src, bot, idx + k, f), split);
    const __m256i r1 = _mm256_permutevar8x32_epi32(lerp4(src, bot, idx + k + 4, _mm_unpackhi_epi64(f, f)), split);
    const __m256i a = _mm256_permute2x128_si256(r0, r1, 0x20);
    const __m256i b = _mm256_permute2x128_si256(r0, r1, 0x31);
    _mm256_storeu_ps(ca + k, _mm256_mul_ps(_mm256_cvtepi32_ps(a), s));
    _mm256_storeu_ps(cb + k, _mm256_mul_ps(_mm256_cvtepi32_ps(b), s));
  }
  rectifyScalar(idx, fr, stride, src, scale, ca, cb, k, end);
}

#endif

}  // namespace

void rectifyChromaCells(const int32_t* index, const uint16_t* frac, int stride, const uint32_t* src, float gain,
                        float* ca, float* cb, size_t n) {
  // The interpolated value carries 2^16 from the weights.
  const float scale = gain * (1.0f / 65536.0f);
#if defined(__x86_64__)
  const auto span = cpuHasAvx2() ? rectifyAvx2 : rectifyScalar;
#else
  const auto span = rectifyScalar;
#endif
  span(index, frac, stride, src, scale, ca, cb, 0, n);
}

void rectifyChromaRows(const RemapTable& table, const uint32_t* src, float gain, float* ca, float* cb,
                       int y_begin, int y_end) {
  const size_t begin = static_cast<size_t>(y_begin) * table.width;
  const size_t end = static_cast<size_t>(y_end) * table.width;
  rectifyChromaCells(table.index.data() + begin, table.frac.data() + begin, table.src_width, src, gain,
                     ca + begin, cb + begin, end - begin);
}

}  // namespace dv

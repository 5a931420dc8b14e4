#include "pipeline/mosaic_binning.h"

#include <cstdint>

#if defined(__x86_64__)
#include <immintrin.h>

#include "pipeline/kernels.h"
#endif

namespace dv {

namespace {

// Rounded mean of two bytes, as the vector instruction computes it. Each
// site's mean is taken in two such steps (down, then across): up to half a
// level high, nothing the coarse search can see.
inline uint8_t avg(int a, int b) { return static_cast<uint8_t>((a + b + 1) >> 1); }

// Output columns [2 * i_begin, 2 * cells) of one output row from input rows
// a and b (two rows apart): column 2i + x is the mean of the four pixels
// at columns 4i + x and 4i + x + 2 of both rows.
void binRowScalar(const uint8_t* a, const uint8_t* b, uint8_t* out, int i_begin, int cells) {
  for (int i = i_begin; i < cells; ++i)
    for (int x = 0; x < 2; ++x) {
      const int c = 4 * i + x;
      out[2 * i + x] = avg(avg(a[c], b[c]), avg(a[c + 2], b[c + 2]));
    }
}

#if defined(__x86_64__)
__attribute__((target("avx2"))) inline __m256i load(const uint8_t* p) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}

// 16 blocks (64 input bytes, 32 output bytes) per step; returns the first
// block not done. Reads up to 2 bytes past the 64 (the +2 loads), so it
// stops a step early.
__attribute__((target("avx2"))) int binRowAvx2(const uint8_t* a, const uint8_t* b, uint8_t* out, int cells) {
  const __m256i low_words = _mm256_set1_epi32(0xffff);
  int i = 0;
  for (; 4 * (i + 16) + 2 <= 4 * cells; i += 16) {
    __m256i half[2];
    for (int h = 0; h < 2; ++h) {
      const int c = 4 * i + 32 * h;
      const __m256i v = _mm256_avg_epu8(load(a + c), load(b + c));
      const __m256i v2 = _mm256_avg_epu8(load(a + c + 2), load(b + c + 2));
      // Byte 4k + x of the mean is output pixel 2k + x: keep the low word of each dword.
      half[h] = _mm256_and_si256(_mm256_avg_epu8(v, v2), low_words);
    }
    const __m256i packed = _mm256_permute4x64_epi64(_mm256_packus_epi32(half[0], half[1]), 0xd8);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + 2 * i), packed);
  }
  return i;
}
#endif

}  // namespace

void binMosaicRows(const cv::Mat& raw, cv::Mat& out, int cell_begin, int cell_end) {
  // Each site of the 2x2 pattern is binned on its own (the two greens
  // included; subsampling averages them), so the pattern needs no cases.
  const int cells = raw.cols / 4;
  for (int j = cell_begin; j < cell_end; ++j)
    for (int y = 0; y < 2; ++y) {
      const uint8_t* a = raw.ptr<uint8_t>(4 * j + y);
      const uint8_t* b = raw.ptr<uint8_t>(4 * j + y + 2);
      uint8_t* o = out.ptr<uint8_t>(2 * j + y);
      int i = 0;
#if defined(__x86_64__)
      if (cpuHasAvx2()) i = binRowAvx2(a, b, o, cells);
#endif
      binRowScalar(a, b, o, i, cells);
    }
}

}  // namespace dv

#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "pipeline/kernels.h"

namespace dv {

namespace {

// Row prefix of the 2x2 box sums from x = x_begin on, continuing from acc,
// plus the row `above` where one is given.
uint32_t boxPrefixScalar(const int32_t* r0, const int32_t* r1, int x_begin, int width, uint32_t acc,
                         const uint32_t* above, uint32_t* out) {
  for (int x = x_begin; x + 1 < width; ++x) {
    acc += static_cast<uint32_t>(r0[x]) + static_cast<uint32_t>(r0[x + 1]) +
           static_cast<uint32_t>(r1[x]) + static_cast<uint32_t>(r1[x + 1]);
    out[x + 1] = above ? above[x + 1] + acc : acc;
  }
  return acc;
}

#if defined(__x86_64__)
__attribute__((target("avx2"))) inline __m256i at(const int32_t* p) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}

// Eight cells at a time: box sums, then an in-register prefix (shifts within
// each 128-bit half, then the low half's total into the high half) plus the
// running total, which grows by the eight cells' total (not through the
// stored prefix, so one step need not wait for the last). Modular, so equal
// to the scalar loop bit for bit.
__attribute__((target("avx2"))) void boxPrefixAvx2(const int32_t* r0, const int32_t* r1, int width,
                                                   const uint32_t* above, uint32_t* out) {
  __m256i carry = _mm256_setzero_si256();
  const __m256i last = _mm256_set1_epi32(7);
  int x = 0;
  for (; x + 9 <= width; x += 8) {
    __m256i v = _mm256_add_epi32(_mm256_add_epi32(at(r0 + x), at(r0 + x + 1)),
                                 _mm256_add_epi32(at(r1 + x), at(r1 + x + 1)));
    v = _mm256_add_epi32(v, _mm256_slli_si256(v, 4));
    v = _mm256_add_epi32(v, _mm256_slli_si256(v, 8));
    v = _mm256_add_epi32(v, _mm256_permute2x128_si256(_mm256_shuffle_epi32(v, 0xff), v, 0x08));
    const __m256i total = _mm256_permutevar8x32_epi32(v, last);
    v = _mm256_add_epi32(v, carry);
    if (above) v = _mm256_add_epi32(v, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(above + x + 1)));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + x + 1), v);
    carry = _mm256_add_epi32(carry, total);
  }
  const uint32_t acc = static_cast<uint32_t>(_mm256_cvtsi256_si32(carry));
  const uint32_t end = boxPrefixScalar(r0, r1, x, width, acc, above, out);
  out[width] = above ? above[width] + end : end;
}
#endif

void boxPrefix(const int32_t* r0, const int32_t* r1, int width, const uint32_t* above, uint32_t* out) {
  out[0] = above ? above[0] : 0;
#if defined(__x86_64__)
  if (cpuHasAvx2()) return boxPrefixAvx2(r0, r1, width, above, out);
#endif
  const uint32_t end = boxPrefixScalar(r0, r1, 0, width, 0, above, out);
  out[width] = above ? above[width] + end : end;
}

}  // namespace

void boxRowPrefix(const int32_t* r0, const int32_t* r1, int width, uint32_t* out) {
  boxPrefix(r0, r1, width, nullptr, out);
}

void boxRowPrefixOnto(const int32_t* r0, const int32_t* r1, int width, const uint32_t* above, uint32_t* out) {
  boxPrefix(r0, r1, width, above, out);
}

void satRowPrefixRow(const int32_t* g, int width, int height, int y, uint32_t* out) {
  if (y + 1 >= height) {  // the last row has no 2x2 box
    for (int x = 0; x <= width; ++x) out[x] = 0;
    return;
  }
  const int32_t* r0 = g + static_cast<size_t>(y) * width;
  boxRowPrefix(r0, r0 + width, width, out);
}

void satRowPrefixRows(const int32_t* g, int width, int height, uint32_t* sat, int y_begin,
                      int y_end) {
  const size_t stride = static_cast<size_t>(width) + 1;
  for (int y = y_begin; y < y_end; ++y) satRowPrefixRow(g, width, height, y, sat + (y + 1) * stride);
}

__attribute__((target_clones("avx2", "default"))) void satColumnPrefix(uint32_t* sat, int width,
                                                                       int height, int x_begin,
                                                                       int x_end) {
  const size_t stride = static_cast<size_t>(width) + 1;
  for (int y = 2; y <= height; ++y) {
    uint32_t* row = sat + y * stride;
    const uint32_t* prev = row - stride;
    for (int x = x_begin; x < x_end; ++x) row[x] += prev[x];
  }
}

}  // namespace dv

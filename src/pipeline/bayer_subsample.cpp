#include "pipeline/bayer_subsample.h"

#include <algorithm>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "pipeline/kernels.h"
#include "pipeline/simd_clones.h"

namespace dv {

BayerSites bayerSites(BayerPattern pattern) {
  switch (pattern) {
    case BayerPattern::GRBG: return {1, 0, 0, 1};
    case BayerPattern::GBRG: return {0, 1, 1, 0};
    case BayerPattern::BGGR: return {1, 1, 0, 0};
    case BayerPattern::RGGB:
    case BayerPattern::None: break;
  }
  return {0, 0, 1, 1};
}

namespace {

// One output row for the sites given at compile time, so the inner loop has
// constant offsets the compiler can vectorise.
template <int RX, int RY, int BX, int BY>
DV_TEMPLATE_AVX2_CLONES void subsampleRow(
    const uint8_t* r_row, const uint8_t* r_nrow, const uint8_t* b_row, const uint8_t* b_nrow,
    const uint8_t* g_row0, const uint8_t* g_row1, int ws, int c0, int c1, uint8_t* out) {
  // Red moves toward +x if it sits at column offset 0, else toward -x.
  constexpr int rs = RX == 0 ? 2 : -2;
  constexpr int bs = BX == 0 ? 2 : -2;
  // Green sites: the two positions that are neither red nor blue; in every
  // pattern they are (1-RX, RY) on the red row and (RX, 1-RY) on the other.
  constexpr int g0x = 1 - RX, g1x = RX;
  auto pixel = [&](int i, int rn, int bn) {
    const int rc = 2 * i + RX, bc = 2 * i + BX;
    uint8_t* o = out + 4 * i;
    o[0] = static_cast<uint8_t>(quarterShift(r_row[rc], r_row[rn], r_nrow[rc], r_nrow[rn]));
    o[1] = static_cast<uint8_t>((g_row0[2 * i + g0x] + g_row1[2 * i + g1x] + 1) >> 1);
    o[2] = static_cast<uint8_t>(quarterShift(b_row[bc], b_row[bn], b_nrow[bc], b_nrow[bn]));
    o[3] = 0;
  };
  // Borders: the neighbour across the image edge is the sample itself.
  const int last = ws - 1;
  for (int i : {0, last}) {
    if (i < c0 || i >= c1) continue;
    const int rn = std::clamp(2 * i + RX + rs, RX, 2 * last + RX);
    const int bn = std::clamp(2 * i + BX + bs, BX, 2 * last + BX);
    pixel(i, rn, bn);
  }
  // Interior: one 32-bit store per pixel so the loop vectorises.
  uint32_t* o32 = reinterpret_cast<uint32_t*>(out);
  const int i_end = std::min(c1, last);
  for (int i = std::max(c0, 1); i < i_end; ++i) {
    const int rc = 2 * i + RX, bc = 2 * i + BX;
    const uint32_t r = (9u * r_row[rc] + 3u * r_row[rc + rs] + 3u * r_nrow[rc] + r_nrow[rc + rs] + 8u) >> 4;
    const uint32_t g = (uint32_t{g_row0[2 * i + g0x]} + g_row1[2 * i + g1x] + 1u) >> 1;
    const uint32_t b = (9u * b_row[bc] + 3u * b_row[bc + bs] + 3u * b_nrow[bc] + b_nrow[bc + bs] + 8u) >> 4;
    o32[i] = r | (g << 8) | (b << 16);
  }
}

#if defined(__x86_64__)
// 8 x 8 block: rows of src (stride src_stride) become rows of dst.
__attribute__((target("avx2"))) void transpose8x8(const uint32_t* src, int src_stride, uint32_t* dst,
                                                  size_t dst_stride) {
  __m256 r[8], t[8], u[8];
  for (int i = 0; i < 8; ++i) r[i] = _mm256_loadu_ps(reinterpret_cast<const float*>(src + i * src_stride));
  for (int i = 0; i < 8; i += 2) {
    t[i] = _mm256_unpacklo_ps(r[i], r[i + 1]);
    t[i + 1] = _mm256_unpackhi_ps(r[i], r[i + 1]);
  }
  for (int i = 0; i < 8; i += 4) {
    u[i] = _mm256_shuffle_ps(t[i], t[i + 2], 0x44);
    u[i + 1] = _mm256_shuffle_ps(t[i], t[i + 2], 0xee);
    u[i + 2] = _mm256_shuffle_ps(t[i + 1], t[i + 3], 0x44);
    u[i + 3] = _mm256_shuffle_ps(t[i + 1], t[i + 3], 0xee);
  }
  for (int i = 0; i < 4; ++i) {
    _mm256_storeu_ps(reinterpret_cast<float*>(dst + i * dst_stride), _mm256_permute2f128_ps(u[i], u[i + 4], 0x20));
    _mm256_storeu_ps(reinterpret_cast<float*>(dst + (i + 4) * dst_stride), _mm256_permute2f128_ps(u[i], u[i + 4], 0x31));
  }
}
#endif

// dst[i * dst_stride + r] = src[r * src_stride + i] for r < rows, i < cols.
void transposeBlock(const uint32_t* src, int src_stride, int rows, int cols, uint32_t* dst,
                    size_t dst_stride) {
  int i = 0;
#if defined(__x86_64__)
  if (rows == 16 && cpuHasAvx2()) {  // the usual case: 64-byte runs per column
    for (; i + 8 <= cols; i += 8) {
      transpose8x8(src + i, src_stride, dst + i * dst_stride, dst_stride);
      transpose8x8(src + 8 * src_stride + i, src_stride, dst + i * dst_stride + 8, dst_stride);
    }
  }
#endif
  for (; i < cols; ++i)
    for (int r = 0; r < rows; ++r) dst[i * dst_stride + r] = src[r * src_stride + i];
}

#if defined(__x86_64__)
// Byte `odd` (0 or 1) of each 16-bit word at p: 16 samples of one site.
template <int Odd>
__attribute__((target("avx2"))) inline __m256i sites(const uint8_t* p) {
  const __m256i w = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
  return Odd ? _mm256_srli_epi16(w, 8) : _mm256_and_si256(w, _mm256_set1_epi16(0xff));
}

// 9:3:3:1 quarter shift of 16 samples (row, its x neighbour at +-2 bytes,
// the next row and its neighbour), in 16 bits (at most 16 * 255 + 8).
template <int Odd, int Step>
__attribute__((target("avx2"))) inline __m256i shifted16(const uint8_t* row, const uint8_t* nrow) {
  const __m256i c = sites<Odd>(row), nx = sites<Odd>(row + Step), ny = sites<Odd>(nrow),
                nxy = sites<Odd>(nrow + Step);
  const __m256i s = _mm256_add_epi16(_mm256_mullo_epi16(c, _mm256_set1_epi16(9)),
                                     _mm256_mullo_epi16(_mm256_add_epi16(nx, ny), _mm256_set1_epi16(3)));
  return _mm256_srli_epi16(_mm256_add_epi16(_mm256_add_epi16(s, nxy), _mm256_set1_epi16(8)), 4);
}

// Two int16 coefficients in every 32-bit lane, for pmaddwd.
__attribute__((target("avx2"))) inline __m256i pair(int lo, int hi) {
  return _mm256_set1_epi32(static_cast<int>((static_cast<uint32_t>(hi) << 16) | (static_cast<uint32_t>(lo) & 0xffffu)));
}

// (k0 r + k1 g + k2 b + 8) >> 4 for the sample halves that unpacklo/hi pick.
__attribute__((target("avx2"))) inline __m256i chroma8(__m256i rg, __m256i b1, __m256i k01, __m256i k2r) {
  return _mm256_srai_epi32(_mm256_add_epi32(_mm256_madd_epi16(rg, k01), _mm256_madd_epi16(b1, k2r)), 4);
}

// Samples at..at+15 of chromaRow's interior.
template <int RX, int BX>
__attribute__((target("avx2"))) inline void chroma16(const uint8_t* r_row, const uint8_t* r_nrow,
                                                     const uint8_t* b_row, const uint8_t* b_nrow,
                                                     const uint8_t* g_row1, int at, __m256i ka01, __m256i ka2r,
                                                     __m256i kb01, __m256i kb2r, uint32_t* out) {
  constexpr int rs = RX == 0 ? 2 : -2;
  constexpr int bs = BX == 0 ? 2 : -2;
  const __m256i one = _mm256_set1_epi16(1);
  const __m256i r = shifted16<RX, rs>(r_row + 2 * at, r_nrow + 2 * at);
  const __m256i b = shifted16<BX, bs>(b_row + 2 * at, b_nrow + 2 * at);
  const __m256i g = _mm256_avg_epu16(sites<1 - RX>(r_row + 2 * at), sites<RX>(g_row1 + 2 * at));
  const __m256i rg_lo = _mm256_unpacklo_epi16(r, g), rg_hi = _mm256_unpackhi_epi16(r, g);
  const __m256i b_lo = _mm256_unpacklo_epi16(b, one), b_hi = _mm256_unpackhi_epi16(b, one);
  const __m256i lo = _mm256_blend_epi16(chroma8(rg_lo, b_lo, ka01, ka2r),
                                        _mm256_slli_epi32(chroma8(rg_lo, b_lo, kb01, kb2r), 16), 0xaa);
  const __m256i hi = _mm256_blend_epi16(chroma8(rg_hi, b_hi, ka01, ka2r),
                                        _mm256_slli_epi32(chroma8(rg_hi, b_hi, kb01, kb2r), 16), 0xaa);
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + at), _mm256_permute2x128_si256(lo, hi, 0x20));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + at + 8), _mm256_permute2x128_si256(lo, hi, 0x31));
}

// The interior loop of chromaRow, 16 samples at a time, the same integer
// arithmetic. A remainder of fewer than 16 samples is done by one more step
// that ends at i_end, overlapping the last (it writes the same values), so
// no sample is left to the scalar loop unless the run is shorter than 16.
// Returns the first sample it did not do.
template <int RX, int BX>
__attribute__((target("avx2"))) int chromaRowAvx2(const uint8_t* r_row, const uint8_t* r_nrow,
                                                  const uint8_t* b_row, const uint8_t* b_nrow,
                                                  const uint8_t* g_row1, int i, int i_end,
                                                  const ChromaFixed& k, uint32_t* out) {
  const __m256i ka01 = pair(k.a[0], k.a[1]), ka2r = pair(k.a[2], 8);
  const __m256i kb01 = pair(k.b[0], k.b[1]), kb2r = pair(k.b[2], 8);
  const int first = i;
  for (; i + 16 <= i_end; i += 16)
    chroma16<RX, BX>(r_row, r_nrow, b_row, b_nrow, g_row1, i, ka01, ka2r, kb01, kb2r, out);
  if (i < i_end && i_end - 16 >= first) {
    chroma16<RX, BX>(r_row, r_nrow, b_row, b_nrow, g_row1, i_end - 16, ka01, ka2r, kb01, kb2r, out);
    i = i_end;
  }
  return i;
}
#endif

template <int RX, int RY, int BX, int BY>
DV_TEMPLATE_AVX2_CLONES void chromaRow(
    const uint8_t* r_row, const uint8_t* r_nrow, const uint8_t* b_row, const uint8_t* b_nrow,
    const uint8_t* g_row0, const uint8_t* g_row1, int ws, int c0, int c1, const ChromaFixed& k,
    uint32_t* out) {
  constexpr int rs = RX == 0 ? 2 : -2;
  constexpr int bs = BX == 0 ? 2 : -2;
  constexpr int g0x = 1 - RX, g1x = RX;
  const int last = ws - 1;
  for (int i : {0, last}) {
    if (i < c0 || i >= c1) continue;
    const int rc = 2 * i + RX, bc = 2 * i + BX;
    const int rn = std::clamp(rc + rs, RX, 2 * last + RX);
    const int bn = std::clamp(bc + bs, BX, 2 * last + BX);
    out[i - c0] = packChroma(k, quarterShift(r_row[rc], r_row[rn], r_nrow[rc], r_nrow[rn]),
                        (g_row0[2 * i + g0x] + g_row1[2 * i + g1x] + 1) >> 1,
                        quarterShift(b_row[bc], b_row[bn], b_nrow[bc], b_nrow[bn]));
  }
  const int ka0 = k.a[0], ka1 = k.a[1], ka2 = k.a[2], kb0 = k.b[0], kb1 = k.b[1], kb2 = k.b[2];
  const int i_end = std::min(c1, last);
  int i = std::max(c0, 1);
#if defined(__x86_64__)
  if (cpuHasAvx2())
    i = chromaRowAvx2<RX, BX>(r_row, r_nrow, b_row, b_nrow, g_row1, i, i_end, k, out - c0);
#endif
  for (; i < i_end; ++i) {
    const int rc = 2 * i + RX, bc = 2 * i + BX;
    const int r = (9 * r_row[rc] + 3 * r_row[rc + rs] + 3 * r_nrow[rc] + r_nrow[rc + rs] + 8) >> 4;
    const int g = (g_row0[2 * i + g0x] + g_row1[2 * i + g1x] + 1) >> 1;
    const int b = (9 * b_row[bc] + 3 * b_row[bc + bs] + 3 * b_nrow[bc] + b_nrow[bc + bs] + 8) >> 4;
    const int a = (ka0 * r + ka1 * g + ka2 * b + 8) >> 4;
    const int c = (kb0 * r + kb1 * g + kb2 * b + 8) >> 4;
    out[i - c0] = (static_cast<uint32_t>(a) & 0xffffu) | (static_cast<uint32_t>(c) << 16);
  }
}

// Sample (i, j) goes to out[(j - oj) * stride + i - oi].
template <int RX, int RY, int BX, int BY>
void chromaRowsT(const cv::Mat& raw, const ChromaFixed& k, uint32_t* out, size_t stride, int oi, int oj,
                 int row_begin, int row_end, int c0, int c1) {
  const int ws = raw.cols / 2, hs = raw.rows / 2;
  constexpr int rdy = RY == 0 ? 1 : -1;
  constexpr int bdy = BY == 0 ? 1 : -1;
  for (int j = row_begin; j < row_end; ++j) {
    const int rj = std::clamp(j + rdy, 0, hs - 1), bj = std::clamp(j + bdy, 0, hs - 1);
    chromaRow<RX, RY, BX, BY>(raw.ptr<uint8_t>(2 * j + RY), raw.ptr<uint8_t>(2 * rj + RY),
                              raw.ptr<uint8_t>(2 * j + BY), raw.ptr<uint8_t>(2 * bj + BY),
                              raw.ptr<uint8_t>(2 * j + RY), raw.ptr<uint8_t>(2 * j + 1 - RY), ws,
                              c0, c1, k, out + (j - oj) * stride + (c0 - oi));
  }
}

// Bytes [b, e) of an image row and of the row below it into the cache.
inline void prefetchRun(const uint8_t* row, int b, int e, size_t step) {
  for (int x = b & ~63; x < e; x += 64) {
    __builtin_prefetch(row + x);
    __builtin_prefetch(row + step + x);
  }
}

// Same rows written transposed (sample (i, j) at (i - oi) * stride + j - oj):
// blocks of 16 rows go through a small buffer, then out as one 64-byte run
// per column.
template <int RX, int RY, int BX, int BY>
void chromaRowsTransposedT(const cv::Mat& raw, const ChromaFixed& k, uint32_t* out, size_t stride, int oi,
                           int oj, int row_begin, int row_end, int c0, int c1) {
  const int ws = raw.cols / 2, hs = raw.rows / 2;
  constexpr int rdy = RY == 0 ? 1 : -1;
  constexpr int bdy = BY == 0 ? 1 : -1;
  constexpr int kRows = 16, kCols = 256;
  uint32_t buf[kRows][kCols];
  for (int j0 = row_begin; j0 < row_end; j0 += kRows) {
    const int rows = std::min(kRows, row_end - j0);
    for (int i0 = c0; i0 < c1; i0 += kCols) {
      const int i1 = std::min(c1, i0 + kCols);
      for (int r = 0; r < rows; ++r) {
        const int j = j0 + r;
        const int rj = std::clamp(j + rdy, 0, hs - 1), bj = std::clamp(j + bdy, 0, hs - 1);
        // A narrow box reads short runs of many image rows, which the
        // hardware prefetcher does not follow: ask for the next block's.
        if (j + kRows < hs) prefetchRun(raw.ptr<uint8_t>(2 * (j + kRows)), 2 * i0, 2 * i1 + 2, raw.step[0]);
        chromaRow<RX, RY, BX, BY>(raw.ptr<uint8_t>(2 * j + RY), raw.ptr<uint8_t>(2 * rj + RY),
                                  raw.ptr<uint8_t>(2 * j + BY), raw.ptr<uint8_t>(2 * bj + BY),
                                  raw.ptr<uint8_t>(2 * j + RY), raw.ptr<uint8_t>(2 * j + 1 - RY), ws,
                                  i0, i1, k, buf[r]);
      }
      transposeBlock(buf[0], kCols, rows, i1 - i0, out + (i0 - oi) * stride + (j0 - oj), stride);
    }
  }
}

template <int RX, int RY, int BX, int BY>
void subsampleRowsT(const cv::Mat& raw, uint8_t* rgbx, int row_begin, int row_end, int c0, int c1) {
  const int ws = raw.cols / 2, hs = raw.rows / 2;
  constexpr int rdy = RY == 0 ? 1 : -1;
  constexpr int bdy = BY == 0 ? 1 : -1;
  for (int j = row_begin; j < row_end; ++j) {
    const int rj = std::clamp(j + rdy, 0, hs - 1), bj = std::clamp(j + bdy, 0, hs - 1);
    subsampleRow<RX, RY, BX, BY>(raw.ptr<uint8_t>(2 * j + RY), raw.ptr<uint8_t>(2 * rj + RY),
                                 raw.ptr<uint8_t>(2 * j + BY), raw.ptr<uint8_t>(2 * bj + BY),
                                 raw.ptr<uint8_t>(2 * j + RY), raw.ptr<uint8_t>(2 * j + 1 - RY), ws, c0, c1,
                                 rgbx + static_cast<size_t>(4) * ws * j);
  }
}

}  // namespace

void subsampleBayerRows(const cv::Mat& raw, BayerPattern pattern, uint8_t* rgbx, int row_begin,
                        int row_end, int col_begin, int col_end) {
  const int ws = raw.cols / 2;
  const int c0 = std::max(0, col_begin), c1 = col_end < 0 ? ws : std::min(ws, col_end);
  switch (pattern) {
    case BayerPattern::GRBG: return subsampleRowsT<1, 0, 0, 1>(raw, rgbx, row_begin, row_end, c0, c1);
    case BayerPattern::GBRG: return subsampleRowsT<0, 1, 1, 0>(raw, rgbx, row_begin, row_end, c0, c1);
    case BayerPattern::BGGR: return subsampleRowsT<1, 1, 0, 0>(raw, rgbx, row_begin, row_end, c0, c1);
    default: return subsampleRowsT<0, 0, 1, 1>(raw, rgbx, row_begin, row_end, c0, c1);
  }
}

namespace {

// Samples (i, j), i in [c0, c1), j in [j0, j1), to out[(j - oj) * stride + i - oi],
// or with i and j exchanged in the output when transposed.
void chromaBox(const cv::Mat& raw, BayerPattern pattern, const ChromaFixed& k, bool transposed, uint32_t* out,
               size_t stride, int oi, int oj, int j0, int j1, int c0, int c1) {
  if (transposed) {
    switch (pattern) {
      case BayerPattern::GRBG: return chromaRowsTransposedT<1, 0, 0, 1>(raw, k, out, stride, oi, oj, j0, j1, c0, c1);
      case BayerPattern::GBRG: return chromaRowsTransposedT<0, 1, 1, 0>(raw, k, out, stride, oi, oj, j0, j1, c0, c1);
      case BayerPattern::BGGR: return chromaRowsTransposedT<1, 1, 0, 0>(raw, k, out, stride, oi, oj, j0, j1, c0, c1);
      default: return chromaRowsTransposedT<0, 0, 1, 1>(raw, k, out, stride, oi, oj, j0, j1, c0, c1);
    }
  }
  switch (pattern) {
    case BayerPattern::GRBG: return chromaRowsT<1, 0, 0, 1>(raw, k, out, stride, oi, oj, j0, j1, c0, c1);
    case BayerPattern::GBRG: return chromaRowsT<0, 1, 1, 0>(raw, k, out, stride, oi, oj, j0, j1, c0, c1);
    case BayerPattern::BGGR: return chromaRowsT<1, 1, 0, 0>(raw, k, out, stride, oi, oj, j0, j1, c0, c1);
    default: return chromaRowsT<0, 0, 1, 1>(raw, k, out, stride, oi, oj, j0, j1, c0, c1);
  }
}

}  // namespace

void bayerChromaRows(const cv::Mat& raw, BayerPattern pattern, const ChromaFixed& k,
                     uint32_t* packed, int row_begin, int row_end, int col_begin, int col_end) {
  const int ws = raw.cols / 2;
  const int c0 = std::max(0, col_begin), c1 = col_end < 0 ? ws : std::min(ws, col_end);
  chromaBox(raw, pattern, k, false, packed, static_cast<size_t>(ws), 0, 0, row_begin, row_end, c0, c1);
}

void bayerChromaRowsTransposed(const cv::Mat& raw, BayerPattern pattern, const ChromaFixed& k,
                               uint32_t* packed_t, size_t stride, int row_begin, int row_end,
                               int col_begin, int col_end) {
  const int ws = raw.cols / 2;
  const int c0 = std::max(0, col_begin), c1 = col_end < 0 ? ws : std::min(ws, col_end);
  chromaBox(raw, pattern, k, true, packed_t, stride, 0, 0, row_begin, row_end, c0, c1);
}

void bayerChromaBox(const cv::Mat& raw, BayerPattern pattern, const ChromaFixed& k, bool transposed,
                    uint32_t* out, size_t stride, int i_begin, int i_end, int j_begin, int j_end) {
  chromaBox(raw, pattern, k, transposed, out, stride, i_begin, j_begin, j_begin, j_end, i_begin, i_end);
}

__attribute__((target_clones("avx2", "default"))) void bgrChromaRows(
    const cv::Mat& raw, const ChromaFixed& k, uint32_t* packed, int row_begin, int row_end,
    int col_begin, int col_end) {
  const int w = raw.cols;
  const int c0 = std::max(0, col_begin), c1 = col_end < 0 ? w : std::min(w, col_end);
  for (int j = row_begin; j < row_end; ++j) {
    const uint8_t* in = raw.ptr<uint8_t>(j);
    uint32_t* o = packed + static_cast<size_t>(w) * j;
    for (int i = c0; i < c1; ++i) o[i] = packChroma(k, in[3 * i + 2], in[3 * i + 1], in[3 * i]);
  }
}

void sampleRgbAt(const cv::Mat& raw, BayerPattern pattern, int i, int j, float rgb[3]) {
  if (pattern == BayerPattern::None || raw.channels() == 3) {
    i = std::clamp(i, 0, raw.cols - 1), j = std::clamp(j, 0, raw.rows - 1);
    const uint8_t* p = raw.ptr<uint8_t>(j) + 3 * i;
    rgb[0] = p[2], rgb[1] = p[1], rgb[2] = p[0];
    return;
  }
  const int ws = raw.cols / 2, hs = raw.rows / 2;
  i = std::clamp(i, 0, ws - 1), j = std::clamp(j, 0, hs - 1);
  const auto s = bayerSites(pattern);
  auto at = [&](int x, int y) { return static_cast<int>(raw.at<uint8_t>(y, x)); };
  // Site (sx, sy) of cell (i, j) moved a quarter cell toward the center.
  auto shifted = [&](int sx, int sy) {
    const int ni = std::clamp(i + (sx == 0 ? 1 : -1), 0, ws - 1);
    const int nj = std::clamp(j + (sy == 0 ? 1 : -1), 0, hs - 1);
    return static_cast<float>(quarterShift(at(2 * i + sx, 2 * j + sy), at(2 * ni + sx, 2 * j + sy),
                                           at(2 * i + sx, 2 * nj + sy), at(2 * ni + sx, 2 * nj + sy)));
  };
  rgb[0] = shifted(s.rx, s.ry);
  rgb[1] = static_cast<float>((at(2 * i + 1 - s.rx, 2 * j + s.ry) + at(2 * i + s.rx, 2 * j + 1 - s.ry) + 1) >> 1);
  rgb[2] = shifted(s.bx, s.by);
}

__attribute__((target_clones("avx2", "default"))) void bgrToRgbxRows(const cv::Mat& raw,
                                                                     uint8_t* rgbx,
                                                                     int row_begin, int row_end,
                                                                     int col_begin, int col_end) {
  const int w = raw.cols;
  const int c0 = std::max(0, col_begin), c1 = col_end < 0 ? w : std::min(w, col_end);
  for (int j = row_begin; j < row_end; ++j) {
    const uint8_t* in = raw.ptr<uint8_t>(j);
    uint8_t* o = rgbx + static_cast<size_t>(4) * w * j;
    for (int i = c0; i < c1; ++i) {
      o[4 * i + 0] = in[3 * i + 2];
      o[4 * i + 1] = in[3 * i + 1];
      o[4 * i + 2] = in[3 * i + 0];
      o[4 * i + 3] = 0;
    }
  }
}

}  // namespace dv

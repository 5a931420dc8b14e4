#include "pipeline/peak_select.h"

#include <algorithm>
#include <cmath>
#if defined(__x86_64__)
#include <immintrin.h>

#include "pipeline/kernels.h"
#endif

namespace dv {

namespace {

__attribute__((target_clones("avx2", "default"))) bool anyAbove(const float* v, float t) {
  int n = 0;
  for (int i = 0; i < 16; ++i) n += v[i] > t;
  return n != 0;
}

// Strict on one side, non-strict on the other: a plateau of equal values
// yields exactly one peak.
inline bool isPeak(const float* row, const float* up, const float* dn, int x, float c) {
  return c > row[x - 1] && c >= row[x + 1] && c > up[x] && c >= dn[x];
}

// Peaks of one row, cells [x, x_end), in rising x; returns the new count
// or -1 when out of room.
inline int scalarPeaks(const float* row, const float* up, const float* dn, const uint8_t* m, int x, int x_end,
                       float threshold, int y, PeakCandidate* out, int count, int capacity) {
  for (; x < x_end; ++x) {
    // Nearly every cell is below the threshold: skip 16 at a time with a
    // vectorisable test before looking at single cells.
    if (x + 16 <= x_end && !anyAbove(row + x, threshold)) {
      x += 15;
      continue;
    }
    const float c = row[x];
    if (!(c > threshold)) continue;
    if (isPeak(row, up, dn, x, c) && m[x]) {
      if (count >= capacity) return -1;
      out[count++] = {x, y, c};
    }
  }
  return count;
}

#if defined(__x86_64__)
// The same test on 8 cells at a time: where many cells pass the threshold
// (carpet texture at a low threshold) the cell-by-cell test is the cost.
// Comparisons are exact, so the peaks are the scalar loop's.
__attribute__((target("avx2"))) int avx2Peaks(const float* row, const float* up, const float* dn, const uint8_t* m,
                                              int x, int x_end, float threshold, int y, PeakCandidate* out,
                                              int count, int capacity) {
  const __m256 t = _mm256_set1_ps(threshold);
  for (; x + 8 <= x_end; x += 8) {
    const __m256 c = _mm256_loadu_ps(row + x);
    __m256 ok = _mm256_cmp_ps(c, t, _CMP_GT_OQ);
    if (_mm256_movemask_ps(ok) == 0) continue;  // most of the plane
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(c, _mm256_loadu_ps(row + x - 1), _CMP_GT_OQ));
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(c, _mm256_loadu_ps(row + x + 1), _CMP_GE_OQ));
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(c, _mm256_loadu_ps(up + x), _CMP_GT_OQ));
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(c, _mm256_loadu_ps(dn + x), _CMP_GE_OQ));
    for (unsigned bits = static_cast<unsigned>(_mm256_movemask_ps(ok)); bits; bits &= bits - 1) {
      const int xi = x + __builtin_ctz(bits);
      if (!m[xi]) continue;
      if (count >= capacity) return -1;
      out[count++] = {xi, y, row[xi]};
    }
  }
  return scalarPeaks(row, up, dn, m, x, x_end, threshold, y, out, count, capacity);
}
#endif

}  // namespace

int findPeakRows(const float* score, const uint8_t* mask, int width, int height, int margin,
                 float threshold, PeakCandidate* out, int count, int capacity, int y_begin,
                 int y_end) {
  y_begin = std::max(y_begin, margin);
  y_end = std::min(y_end, height - margin);
  for (int y = y_begin; y < y_end; ++y) {
    const float* row = score + static_cast<size_t>(y) * width;
    const float* up = row - width;
    const float* dn = row + width;
    const uint8_t* m = mask + static_cast<size_t>(y) * width;
    const int x_end = width - margin;
    // The mask is read only at peaks, too sparsely for the hardware to
    // fetch it ahead, and is seldom in cache: ask for the next row's (the
    // banded pass scans one row at a time, the next one a little later).
    if (y + 1 < height - margin)
      for (int x = margin & ~63; x < x_end; x += 64) __builtin_prefetch(m + width + x);
#if defined(__x86_64__)
    const int n = cpuHasAvx2() ? avx2Peaks(row, up, dn, m, margin, x_end, threshold, y, out, count, capacity)
                               : scalarPeaks(row, up, dn, m, margin, x_end, threshold, y, out, count, capacity);
#else
    const int n = scalarPeaks(row, up, dn, m, margin, x_end, threshold, y, out, count, capacity);
#endif
    if (n < 0) return capacity;
    count = n;
  }
  return count;
}

int findPeaksNear(const float* score, const uint8_t* mask, int width, int height, int margin,
                  float threshold, const GridPx* near, int n, const BlobSpacing& reach,
                  std::vector<std::pair<int, int>>& spans, PeakCandidate* out, int count, int capacity,
                  int y_begin, int y_end) {
  y_begin = std::max(y_begin, margin);
  y_end = std::min(y_end, height - margin);
  const double r = reach.distance();
  int lo = 0, hi = 0;  // positions whose disc may reach the row
  for (int y = y_begin; y < y_end; ++y) {
    while (lo < n && near[lo].y < y - r - 1) ++lo;
    while (hi < n && near[hi].y <= y + r + 1) ++hi;
    if (lo >= hi) continue;
    // Each disc's columns on this row, one cell wider (the distance test
    // on the peaks decides), merged so every cell is tested once.
    spans.clear();
    for (int i = lo; i < hi; ++i) {
      const double dy = near[i].y - y;
      if (std::abs(dy) > r + 1) continue;
      const double half = std::sqrt(std::max(0.0, r * r - dy * dy));
      const int x0 = std::max(margin, static_cast<int>(std::ceil(near[i].x - half)) - 1);
      const int x1 = std::min(width - margin - 1, static_cast<int>(std::floor(near[i].x + half)) + 1);
      if (x0 <= x1) spans.emplace_back(x0, x1);
    }
    std::sort(spans.begin(), spans.end());
    const size_t row_at = static_cast<size_t>(y) * width;
    const float* row = score + row_at;
    const float* up = row - width;
    const float* dn = row + width;
    int x = margin;
    for (const auto& [a, b] : spans) {
      for (x = std::max(x, a); x <= b; ++x) {
        if (x + 16 <= b + 1 && !anyAbove(row + x, threshold)) {
          x += 15;
          continue;
        }
        const float c = row[x];
        if (!(c > threshold) || !isPeak(row, up, dn, x, c) || !mask[row_at + x] || !reach.nearKept(x, y))
          continue;
        if (count >= capacity) return count;
        out[count++] = {x, y, c};
      }
    }
  }
  return count;
}

GridPx interpolatePeak(const float* score, int width, int x, int y) {
  const float* row = score + static_cast<size_t>(y) * width;
  auto offset = [](float l, float c, float r) {
    const float d = l - 2 * c + r;
    if (!(d < 0)) return 0.0f;
    return std::clamp(0.5f * (l - r) / d, -0.5f, 0.5f);
  };
  return {x + offset(row[x - 1], row[x], row[x + 1]),
          y + offset(row[x - width], row[x], row[x + width])};
}

}  // namespace dv

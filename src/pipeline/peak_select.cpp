#include "pipeline/peak_select.h"

#include <algorithm>
#include <cmath>

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
    for (int x = margin; x < x_end; ++x) {
      // Nearly every cell is below the threshold: skip 16 at a time with a
      // vectorisable test before looking at single cells.
      if (x + 16 <= x_end && !anyAbove(row + x, threshold)) {
        x += 15;
        continue;
      }
      const float c = row[x];
      if (!(c > threshold)) continue;
      if (isPeak(row, up, dn, x, c) && m[x]) {
        if (count >= capacity) return count;
        out[count++] = {x, y, c};
      }
    }
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

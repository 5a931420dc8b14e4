#include "pipeline/peak_select.h"

#include <algorithm>

namespace dv {

namespace {

__attribute__((target_clones("avx2", "default"))) bool anyAbove(const float* v, float t) {
  int n = 0;
  for (int i = 0; i < 16; ++i) n += v[i] > t;
  return n != 0;
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
      // Strict on one side, non-strict on the other: a plateau of equal
      // values yields exactly one peak.
      if (c > row[x - 1] && c >= row[x + 1] && c > up[x] && c >= dn[x] && m[x]) {
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

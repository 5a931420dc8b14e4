// 4-way peak search: the vectorised row scan against a cell-by-cell
// reference, on planes dense with small maxima and equal neighbours (where
// the strict / non-strict sides decide), with a mask and a full list.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "pipeline/peak_select.h"

namespace dv {
namespace {

std::vector<PeakCandidate> referencePeaks(const std::vector<float>& s, const std::vector<uint8_t>& mask, int w,
                                          int h, int margin, float threshold, int capacity) {
  std::vector<PeakCandidate> out;
  for (int y = margin; y < h - margin; ++y)
    for (int x = margin; x < w - margin; ++x) {
      const size_t k = static_cast<size_t>(y) * w + x;
      const float c = s[k];
      if (!(c > threshold) || !mask[k]) continue;
      if (c > s[k - 1] && c >= s[k + 1] && c > s[k - w] && c >= s[k + w]) {
        if (static_cast<int>(out.size()) >= capacity) return out;
        out.push_back({x, y, c});
      }
    }
  return out;
}

TEST(PeakSelect, RowScanFindsTheCellByCellPeaksInOrder) {
  std::mt19937 rng(7);
  const int w = 203, h = 61, margin = 3;  // odd width: a scalar tail after the 8-cell steps
  std::vector<float> s(static_cast<size_t>(w) * h);
  std::vector<uint8_t> mask(s.size());
  // Values on a coarse ladder, so that equal neighbours are common.
  std::uniform_int_distribution<int> level(0, 6);
  for (auto& v : s) v = 0.001f * level(rng);
  for (size_t k = 0; k < mask.size(); ++k) mask[k] = (k * 7919) % 11 != 0;
  const float threshold = 0.0025f;
  const std::vector<PeakCandidate> want = referencePeaks(s, mask, w, h, margin, threshold, 1 << 20);
  ASSERT_GT(want.size(), 500u);  // a dense plane: most 8-cell steps hold a peak
  std::vector<PeakCandidate> got(want.size() + 10);
  const int n = findPeakRows(s.data(), mask.data(), w, h, margin, threshold, got.data(), 0,
                             static_cast<int>(got.size()), 0, h);
  ASSERT_EQ(n, static_cast<int>(want.size()));
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(got[i].x, want[i].x) << i;
    EXPECT_EQ(got[i].y, want[i].y) << i;
    EXPECT_EQ(got[i].score, want[i].score) << i;
  }
  // A list that fills up keeps the first peaks in row order.
  const int cap = static_cast<int>(want.size() / 3);
  const int m = findPeakRows(s.data(), mask.data(), w, h, margin, threshold, got.data(), 0, cap, 0, h);
  ASSERT_EQ(m, cap);
  EXPECT_EQ(got[cap - 1].x, want[cap - 1].x);
  EXPECT_EQ(got[cap - 1].y, want[cap - 1].y);
}

}  // namespace
}  // namespace dv

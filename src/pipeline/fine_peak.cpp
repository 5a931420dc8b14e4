#include "pipeline/fine_peak.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "pipeline/kernels.h"
#include "pipeline/peak_select.h"
#include "pipeline/score_windows.h"
#include "pipeline/streak_score.h"

namespace dv {

void FinePeak::configure(const RemapTable& table, const FinePeakSpec& spec, BayerPattern pattern,
                         const ChromaFixed& k) {
  table_ = &table;
  spec_ = spec;
  pattern_ = pattern;
  k_ = k;
  n_ = spec.max_side + 2 * spec.margin;
  const size_t cells = static_cast<size_t>(n_) * n_;
  index_.assign(cells, 0);
  ca_.assign(cells, 0);
  cb_.assign(cells, 0);
  score_.assign(cells, 0);
  // Samples under the window, full image rows: the cells are about a
  // sample apart, so twice the window's side (plus the bilinear neighbour)
  // in rows holds them unless the grid is much finer than the samples;
  // larger boxes are refused.
  box_.assign(static_cast<size_t>(table.src_width) * (2 * n_ + 2), 0);
}

bool FinePeak::rectify(const cv::Mat& raw, float gain, int x0, int y0, int w, int h) {
  const RemapTable& t = *table_;
  // The window's table rows lie a grid row apart: ask for all of them now,
  // so that they arrive while the box is made.
  for (int y = 0; y < h; ++y) {
    const size_t k = static_cast<size_t>(y0 + y) * t.width + x0;
    for (int x = 0; x < w; x += 16) __builtin_prefetch(t.index.data() + k + x);
    __builtin_prefetch(t.index.data() + k + w - 1);
    for (int x = 0; x < w; x += 32) __builtin_prefetch(t.frac.data() + k + x);
    __builtin_prefetch(t.frac.data() + k + w - 1);
  }
  // The samples the window reads: its box in the subsampled image, from
  // the window's border cells (the table is a smooth map, so its extremes
  // lie there), stored with the image's row stride so that a cell's sample
  // is its table index less the box origin.
  int i_begin = INT_MAX, i_end = 0, j_begin = INT_MAX, j_end = 0;
  auto extend = [&](int x, int y) {
    const int32_t idx = t.index[static_cast<size_t>(y0 + y) * t.width + x0 + x];
    const int i = idx % t.src_width, j = idx / t.src_width;
    i_begin = std::min(i_begin, i), i_end = std::max(i_end, i + 2);
    j_begin = std::min(j_begin, j), j_end = std::max(j_end, j + 2);
  };
  for (int x = 0; x < w; ++x) extend(x, 0), extend(x, h - 1);
  for (int y = 0; y < h; ++y) extend(0, y), extend(w - 1, y);
  const int stride = t.src_width;
  if (static_cast<size_t>(stride) * (j_end - j_begin) > box_.size()) return false;
  bayerChromaBox(raw, pattern_, k_, false, box_.data(), stride, i_begin, i_end, j_begin, j_end);
  const int32_t base = j_begin * stride + i_begin;
  for (int y = 0; y < h; ++y) {
    const size_t k = static_cast<size_t>(y0 + y) * t.width + x0;
    int32_t* rel = index_.data() + static_cast<size_t>(y) * w;
    for (int x = 0; x < w; ++x) rel[x] = t.index[k + x] - base;
    rectifyChromaCells(rel, t.frac.data() + k, stride, box_.data(), gain, ca_.data() + static_cast<size_t>(y) * w,
                       cb_.data() + static_cast<size_t>(y) * w, w);
  }
  return true;
}

GridPx FinePeak::streak(const cv::Mat& raw, float gain, const StreakFit& fit) {
  const RemapTable& t = *table_;
  const int reach = static_cast<int>(std::ceil(std::hypot(fit.along, fit.across))) + 1;
  const int x0 = std::max(0, static_cast<int>(std::floor(fit.cx)) - reach);
  const int y0 = std::max(0, static_cast<int>(std::floor(fit.cy)) - reach);
  const int w = std::min({t.width, x0 + 2 * reach + 2, x0 + n_}) - x0;
  const int h = std::min({t.height, y0 + 2 * reach + 2, y0 + n_}) - y0;
  if (!fit.ok || w <= 0 || h <= 0 || !rectify(raw, gain, x0, y0, w, h)) return {fit.cx, fit.cy};
  return streakCentroid(fit, ca_.data(), cb_.data(), x0, y0, w, h);
}

int FinePeak::peaks(const cv::Mat& raw, float gain, const CellRect& region, const uint8_t* mask,
                    const Thresholds& th, const BlobSpacing& near, FinePeakFound* out, int capacity) {
  const RemapTable& t = *table_;
  const int m = spec_.margin;
  // The window: the region and the margin its scores need, inside the grid
  // (cells next to the grid's edges have no score in the full pass either).
  const int x0 = std::max(0, region.x0 - m), y0 = std::max(0, region.y0 - m);
  const int w = std::min({t.width, region.x1 + m, x0 + n_}) - x0;
  const int h = std::min({t.height, region.y1 + m, y0 + n_}) - y0;
  if (w <= 2 * m || h <= 2 * m || !rectify(raw, gain, x0, y0, w, h)) return 0;
  quadrantMinScoreFromChroma(ca_.data(), cb_.data(), w, h, spec_.gradient_scale, spec_.quadrant_r, spec_.inner_q,
                             score_.data(), 0, h, ring_);

  // The full pass's 4-way peaks in the region, among window cells with a
  // full score window.
  const int lx = std::max(m, region.x0 - x0), hx = std::min(w - m, region.x1 - x0);
  const int ly = std::max(m, region.y0 - y0), hy = std::min(h - m, region.y1 - y0);
  int count = 0;
  for (int y = ly; y < hy; ++y)
    for (int x = lx; x < hx; ++x) {
      const float* c = score_.data() + static_cast<size_t>(y) * w + x;
      if (!(*c > th.raw_low && *c > c[-1] && *c >= c[1] && *c > c[-w] && *c >= c[w])) continue;
      if (!mask[static_cast<size_t>(y0 + y) * t.width + x0 + x]) continue;
      // Below the raw score a blob needs, only a weak peak near a blob.
      if (!(*c > th.raw_strong) && !near.nearKept(x0 + x, y0 + y)) continue;
      const float r = *c / (windowGradientEnergy(ca_.data(), cb_.data(), w, spec_.gradient_scale, x, y,
                                                 spec_.energy_r, *c / th.low) +
                            kEnergyFloor);
      if (!(r > th.low)) continue;
      if (count == capacity) return count;
      const GridPx p = interpolatePeak(score_.data(), w, x, y);
      out[count++] = {x0 + x, y0 + y, {p.x + x0, p.y + y0}, r};
    }
  return count;
}

}  // namespace dv

#include "pipeline/fine_peak.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "pipeline/kernels.h"
#include "pipeline/peak_select.h"
#include "pipeline/score_windows.h"

namespace dv {

void FinePeak::configure(const RemapTable& table, const FinePeakSpec& spec, BayerPattern pattern,
                         const ChromaFixed& k) {
  table_ = &table;
  spec_ = spec;
  pattern_ = pattern;
  k_ = k;
  n_ = 2 * (spec.search + spec.margin) + 1;
  const size_t cells = static_cast<size_t>(n_) * n_;
  index_.assign(cells, 0);
  ca_.assign(cells, 0);
  cb_.assign(cells, 0);
  score_.assign(cells, 0);
  // Samples under the window: the cells are about a sample apart, so a
  // box of twice the window's side (plus the bilinear neighbour) holds them
  // unless the grid is much finer than the samples; larger boxes are refused.
  box_.assign(static_cast<size_t>(2 * n_ + 2) * (2 * n_ + 2), 0);
}

bool FinePeak::refine(const cv::Mat& raw, float gain, GridPx guess, GridPx& at, float& ratio) {
  const RemapTable& t = *table_;
  const int half = spec_.search + spec_.margin;
  const int cx = static_cast<int>(std::lround(guess.x)), cy = static_cast<int>(std::lround(guess.y));
  // Next to the grid's edges the window is moved inside: cells there have
  // no score in the full pass either.
  if (n_ > t.width || n_ > t.height) return false;
  const int x0 = std::clamp(cx - half, 0, t.width - n_), y0 = std::clamp(cy - half, 0, t.height - n_);

  // The samples the window reads: its box in the subsampled image.
  int i_begin = INT_MAX, i_end = 0, j_begin = INT_MAX, j_end = 0;
  for (int y = 0; y < n_; ++y) {
    const int32_t* row = t.index.data() + static_cast<size_t>(y0 + y) * t.width + x0;
    for (int x = 0; x < n_; ++x) {
      const int i = row[x] % t.src_width, j = row[x] / t.src_width;
      i_begin = std::min(i_begin, i), i_end = std::max(i_end, i + 2);
      j_begin = std::min(j_begin, j), j_end = std::max(j_end, j + 2);
    }
  }
  const int stride = i_end - i_begin;
  if (static_cast<size_t>(stride) * (j_end - j_begin) > box_.size()) return false;
  bayerChromaBox(raw, pattern_, k_, false, box_.data(), stride, i_begin, i_end, j_begin, j_end);
  for (int y = 0; y < n_; ++y) {
    const size_t k = static_cast<size_t>(y0 + y) * t.width + x0;
    int32_t* rel = index_.data() + static_cast<size_t>(y) * n_;
    for (int x = 0; x < n_; ++x) {
      const int i = t.index[k + x] % t.src_width, j = t.index[k + x] / t.src_width;
      rel[x] = (j - j_begin) * stride + (i - i_begin);
    }
    rectifyChromaCells(rel, t.frac.data() + k, stride, box_.data(), gain, ca_.data() + static_cast<size_t>(y) * n_,
                       cb_.data() + static_cast<size_t>(y) * n_, n_);
  }
  quadrantMinScoreFromChroma(ca_.data(), cb_.data(), n_, n_, spec_.gradient_scale, spec_.quadrant_r, spec_.inner_q,
                             score_.data(), 0, n_, ring_);

  // The peaks (the full pass's 4-way test) within `search` of the guess's
  // cell, among window cells with a full score window; the one of highest
  // ratio, as the full pass keeps the strongest of peaks this close.
  const int m = spec_.margin;
  const int lx = std::max(m, cx - x0 - spec_.search), hx = std::min(n_ - 1 - m, cx - x0 + spec_.search);
  const int ly = std::max(m, cy - y0 - spec_.search), hy = std::min(n_ - 1 - m, cy - y0 + spec_.search);
  int bx = -1, by = -1;
  float best = 0;
  for (int y = ly; y <= hy; ++y)
    for (int x = lx; x <= hx; ++x) {
      const float* c = score_.data() + static_cast<size_t>(y) * n_ + x;
      if (!(*c > 0 && *c > c[-1] && *c >= c[1] && *c > c[-n_] && *c >= c[n_])) continue;
      const float r = *c / (windowGradientEnergy(ca_.data(), cb_.data(), n_, spec_.gradient_scale, x, y,
                                                 spec_.energy_r) + kEnergyFloor);
      if (r > best) best = r, bx = x, by = y;
    }
  if (bx < 0) return false;
  const GridPx p = interpolatePeak(score_.data(), n_, bx, by);
  at = {p.x + x0, p.y + y0};
  ratio = best;
  return true;
}

}  // namespace dv

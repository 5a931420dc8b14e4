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
  const int x0 = cx - half, y0 = cy - half;
  if (x0 < 0 || y0 < 0 || x0 + n_ > t.width || y0 + n_ > t.height) return false;

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

  // The highest score within `search` of the guess's cell.
  int bx = half, by = half;
  float best = -INFINITY;
  for (int y = half - spec_.search; y <= half + spec_.search; ++y)
    for (int x = half - spec_.search; x <= half + spec_.search; ++x) {
      const float s = score_[static_cast<size_t>(y) * n_ + x];
      if (s > best) best = s, bx = x, by = y;
    }
  if (!(best > 0) || std::abs(bx - half) == spec_.search || std::abs(by - half) == spec_.search) return false;
  const GridPx p = interpolatePeak(score_.data(), n_, bx, by);
  const float energy = windowGradientEnergy(ca_.data(), cb_.data(), n_, spec_.gradient_scale, bx, by, spec_.energy_r);
  at = {p.x + x0, p.y + y0};
  ratio = best / (energy + kEnergyFloor);
  return true;
}

}  // namespace dv

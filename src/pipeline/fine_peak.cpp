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
  n_ = 0;
  reserve(spec.max_side + 2 * spec.margin);
}

void FinePeak::reserve(int side) {
  if (side <= n_) return;
  n_ = side;
  const size_t cells = static_cast<size_t>(n_) * n_;
  index_.assign(cells, 0);
  ca_.assign(cells, 0);
  cb_.assign(cells, 0);
  score_.assign(cells, 0);
  // Samples under the window, full image rows: the cells are about a
  // sample apart, so twice the window's side (plus the bilinear neighbour)
  // in rows holds them unless the grid is much finer than the samples;
  // larger boxes are refused. None under full sampling (the frame's plane).
  if (!plane_) box_.assign(static_cast<size_t>(table_->src_width) * (2 * n_ + 2), 0);
  const int blocks = (n_ + kFormBlock - 1) / kFormBlock + 1;
  window_forms_.coef.assign(6 * static_cast<size_t>(blocks) * blocks, 0.f);
  window_forms_.plain.assign(static_cast<size_t>(blocks) * blocks, 1);
  window_forms_.plain_row.assign(blocks, 1);
}

void FinePeak::usePlane(const uint32_t* plane, const GradientForms& forms) {
  plane_ = plane;
  forms_ = forms.any ? &forms : nullptr;
  box_.clear();
  box_.shrink_to_fit();
  // Room to move a window's origin back onto a block corner.
  if (forms_) reserve(n_ + kFormBlock);
}

bool FinePeak::plainOver(int x0, int y0, int x1, int y1) const {
  const int bx1 = std::min(forms_->blocks_x, (x1 + kFormBlock - 1) / kFormBlock);
  const int by1 = std::min(forms_->blocks_y, (y1 + kFormBlock - 1) / kFormBlock);
  for (int by = y0 / kFormBlock; by < by1; ++by) {
    if (forms_->plain_row[by]) continue;
    for (int bx = x0 / kFormBlock; bx < bx1; ++bx)
      if (!forms_->plain[static_cast<size_t>(by) * forms_->blocks_x + bx]) return false;
  }
  return true;
}

// The grid's forms for window cells [x0, x0 + w) x [y0, y0 + h), x0 and y0
// on block corners, into window_forms_ (window coordinates).
const GradientForms* FinePeak::windowForms(int x0, int y0, int w, int h) {
  if (!forms_) return nullptr;
  GradientForms& f = window_forms_;
  const int bx0 = x0 / kFormBlock, by0 = y0 / kFormBlock;
  f.blocks_x = std::min(forms_->blocks_x - bx0, (w + kFormBlock - 1) / kFormBlock);
  f.blocks_y = std::min(forms_->blocks_y - by0, (h + kFormBlock - 1) / kFormBlock);
  f.any = false;
  for (int by = 0; by < f.blocks_y; ++by) {
    const size_t from = static_cast<size_t>(by0 + by) * forms_->blocks_x + bx0;
    const size_t to = static_cast<size_t>(by) * f.blocks_x;
    std::copy_n(forms_->coef.data() + 6 * from, 6 * f.blocks_x, f.coef.data() + 6 * to);
    std::copy_n(forms_->plain.data() + from, f.blocks_x, f.plain.data() + to);
    f.plain_row[by] = static_cast<uint8_t>(
        std::all_of(f.plain.data() + to, f.plain.data() + to + f.blocks_x, [](uint8_t p) { return p != 0; }));
    f.any = f.any || !f.plain_row[by];
  }
  return f.any ? &f : nullptr;
}

bool FinePeak::rectify(const cv::Mat& raw, float gain, int x0, int y0, int w, int h) {
  const RemapTable& t = *table_;
  if (plane_) {  // the frame's samples, as the full pass reads them
    for (int y = 0; y < h; ++y) {
      const size_t k = static_cast<size_t>(y0 + y) * t.width + x0;
      rectifyChromaCells(t.index.data() + k, t.frac.data() + k, t.src_width, plane_, gain,
                         ca_.data() + static_cast<size_t>(y) * w, cb_.data() + static_cast<size_t>(y) * w, w);
    }
    return true;
  }
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

void FinePeak::configureStreaks(const StreakWindows& w, const uint8_t* lattice_mask, int reach) {
  streak_ = w;
  lattice_mask_ = lattice_mask;
  reach_ = reach;
  // The patch: the searched lattice cells, their neighbours (the peak
  // test) and the footprint's margin on every side, in whole lattice cells
  // so that its lattice is the grid's.
  const int margin = (w.margin + kStreakLatticeStep - 1) / kStreakLatticeStep;
  side_ = 2 * (reach + 1 + margin) + 1;
  patch_ = w;
  patch_.coarse_width = patch_.coarse_height = side_ * kStreakLatticeStep;
  patch_.lattice_width = patch_.lattice_height = side_;
  const size_t lattice = static_cast<size_t>(side_) * side_;
  patch_coarse_.assign(2 * lattice * kStreakLatticeStep * kStreakLatticeStep, 0);
  patch_score_.assign(lattice, 0);
  patch_orient_.assign(lattice, 0);
  patch_mask_.assign(lattice, 0);
  patch_peaks_.resize(lattice);
  // Rectified chroma for the whole patch.
  reserve(patch_.coarse_width * w.factor);
}

int FinePeak::streaks(const cv::Mat& raw, float gain, const StreakLevels& levels, GridPx c, Streak* out,
                      int capacity) {
  const StreakWindows& w = streak_;
  const int f = w.factor, cell = f * kStreakLatticeStep;  // grid cells per lattice cell
  // The patch's first lattice cell, kept inside the grid's lattice.
  const int max_x = w.coarse_width / kStreakLatticeStep - side_, max_y = w.coarse_height / kStreakLatticeStep - side_;
  if (side_ == 0 || max_x < 0 || max_y < 0) return 0;
  const int li = static_cast<int>(std::lround((c.x - 0.5 * (f - 1)) / cell));
  const int lj = static_cast<int>(std::lround((c.y - 0.5 * (f - 1)) / cell));
  const int half = side_ / 2;
  const int lx0 = std::clamp(li - half, 0, max_x), ly0 = std::clamp(lj - half, 0, max_y);
  const int side = patch_.coarse_width * f;
  if (!rectify(raw, gain, lx0 * cell, ly0 * cell, side, side)) return 0;
  streakCoarseRows(ca_.data(), cb_.data(), side, patch_, patch_coarse_.data(), 0, patch_.coarse_height);
  // Only the searched cells' rows and their neighbours are scored.
  const int sx0 = std::max(li - reach_, lx0 + 1) - lx0, sx1 = std::min(li + reach_, lx0 + side_ - 2) - lx0;
  const int sy0 = std::max(lj - reach_, ly0 + 1) - ly0, sy1 = std::min(lj + reach_, ly0 + side_ - 2) - ly0;
  if (sx0 > sx1 || sy0 > sy1) return 0;
  streakScoreRows(patch_coarse_.data(), patch_, levels, patch_score_.data(), patch_orient_.data(), sy0 - 1, sy1 + 2);
  std::fill(patch_mask_.begin(), patch_mask_.end(), uint8_t{0});
  for (int y = sy0; y <= sy1; ++y)
    for (int x = sx0; x <= sx1; ++x)
      patch_mask_[static_cast<size_t>(y) * side_ + x] =
          lattice_mask_[static_cast<size_t>(ly0 + y) * w.lattice_width + lx0 + x];
  const int n = findStreakPeakRows(patch_score_.data(), patch_mask_.data(), patch_, patch_peaks_.data(), 0,
                                   static_cast<int>(patch_peaks_.size()), sy0, sy1 + 1);
  int count = 0;
  for (int i = 0; i < n && count < capacity; ++i) {
    const StreakPeak& p = patch_peaks_[i];
    const int o = patch_orient_[static_cast<size_t>(p.y) * side_ + p.x];
    const GridPx at = streakCentroid(streakFit(patch_coarse_.data(), patch_, p, o), ca_.data(), cb_.data(), 0, 0,
                                     side, side);
    out[count++] = {{p.x + lx0, p.y + ly0, p.score}, o, {at.x + lx0 * cell, at.y + ly0 * cell}};
  }
  return count;
}

int FinePeak::peaks(const cv::Mat& raw, float gain, const CellRect& region, const uint8_t* mask,
                    const Thresholds& th, const BlobSpacing& near, FinePeakFound* out, int capacity) {
  const RemapTable& t = *table_;
  const int m = spec_.margin;
  // The window: the region and the margin its scores need, inside the grid
  // (cells next to the grid's edges have no score in the full pass either).
  int x0 = std::max(0, region.x0 - m), y0 = std::max(0, region.y0 - m);
  // Where it reaches a whitened block, its origin moves back onto a block
  // corner (the forms are per block).
  const bool whiten = forms_ && !plainOver(x0, y0, region.x1 + m, region.y1 + m);
  if (whiten) x0 = x0 / kFormBlock * kFormBlock, y0 = y0 / kFormBlock * kFormBlock;
  const int w = std::min({t.width, region.x1 + m, x0 + n_}) - x0;
  const int h = std::min({t.height, region.y1 + m, y0 + n_}) - y0;
  if (w <= 2 * m || h <= 2 * m || !rectify(raw, gain, x0, y0, w, h)) return 0;
  const GradientForms* forms = whiten ? windowForms(x0, y0, w, h) : nullptr;
  quadrantMinScoreFromChroma(ca_.data(), cb_.data(), w, h, spec_.gradient_scale, spec_.quadrant_r, spec_.inner_q,
                             score_.data(), 0, h, ring_, forms);

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
      const float stop = *c / th.low;
      const float energy =
          !forms || forms->plainAt(x, y)
              ? windowGradientEnergy(ca_.data(), cb_.data(), w, spec_.gradient_scale, x, y, spec_.energy_r, stop)
              : windowGradientEnergyForm(ca_.data(), cb_.data(), w, spec_.gradient_scale, x, y, spec_.energy_r,
                                         forms->block(x, y) + 3, stop);
      const float r = *c / (energy + kEnergyFloor);
      if (!(r > th.low)) continue;
      if (count == capacity) return count;
      const GridPx p = interpolatePeak(score_.data(), w, x, y);
      out[count++] = {x0 + x, y0 + y, {p.x + x0, p.y + y0}, r};
    }
  return count;
}

}  // namespace dv

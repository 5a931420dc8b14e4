#pragma once
// Places a blob found by the coarse search (coarse_search.h) on the full
// grid: rectifies a small window of full-grid cells around the coarse
// position straight from the mosaic, scores it with the same gradient dot
// product and quadrant score as the full pass, and takes the score's peak
// near the guess with quadratic interpolation. Inside the window the scores
// are those the full pass would compute, so the position is the full grid's.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "core/units.h"
#include "pipeline/bayer_subsample.h"
#include "pipeline/remap_table.h"

namespace dv {

struct FinePeakSpec {
  int search = 3;             // cells around the guess where the peak may lie
  int margin = 1;             // cells a score needs around it (ScoreWindows::margin)
  double gradient_scale = 1;  // cells
  int quadrant_r = 2, inner_q = 0;
  int energy_r = 2;           // ratio window (cells)
};

class FinePeak {
 public:
  // table: the full grid's remap table for Bayer 2x2 subsampling (not
  // transposed). Sizes the scratch once.
  void configure(const RemapTable& table, const FinePeakSpec& spec, BayerPattern pattern, const ChromaFixed& k);
  // The score peak within `search` cells of `guess` (full-grid cells) with
  // the highest ratio score (score over window energy plus the floor),
  // interpolated, and that ratio. False, with nothing written, where no
  // peak lies there (the coarse peak was noise, or its blob lies beyond).
  bool refine(const cv::Mat& raw, float gain, GridPx guess, GridPx& at, float& ratio);

 private:
  const RemapTable* table_ = nullptr;
  FinePeakSpec spec_;
  BayerPattern pattern_ = BayerPattern::RGGB;
  ChromaFixed k_{};
  int n_ = 0;  // window side (cells)
  std::vector<uint32_t> box_, ring_;
  std::vector<int32_t> index_;
  std::vector<float> ca_, cb_, score_;
};

}  // namespace dv

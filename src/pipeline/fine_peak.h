#pragma once
// The full grid's blob score near the blobs of the coarse search
// (pipeline_options.h): a window of full-grid cells around a coarse blob is
// rectified straight from the mosaic and scored with the same gradient dot
// product, quadrant score and ratio test as the full pass, and its peaks are
// taken with the full pass's 4-way test and quadratic interpolation. Inside
// the window the scores are those the full pass computes, so the peaks are
// the full grid's. Under full Bayer sampling (a sample per pixel) the window
// reads the samples the coarse pass made for the whole frame, and where the
// view stretches blobs it whitens the gradient as the full pass does.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "core/units.h"
#include "pipeline/blob_spacing.h"
#include "pipeline/bayer_subsample.h"
#include "pipeline/remap_table.h"
#include "pipeline/streak_score.h"
#include "pipeline/view_stretch.h"

namespace dv {

struct FinePeakSpec {
  int max_side = 16;          // cells: the largest region taken at once
  int margin = 1;             // cells a score needs around it (ScoreWindows::margin)
  double gradient_scale = 1;  // cells
  int quadrant_r = 2, inner_q = 0;
  int energy_r = 2;           // ratio window (cells)
};

// Cells [x0, x1) x [y0, y1) of the full grid.
struct CellRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct FinePeakFound {
  int x = 0, y = 0;  // full-grid cell
  GridPx at;         // interpolated
  float ratio = 0;   // score over window energy plus the floor
};

class FinePeak {
 public:
  // table: the full grid's remap table (not transposed), for Bayer 2x2
  // subsampling unless usePlane follows. Sizes the scratch once.
  void configure(const RemapTable& table, const FinePeakSpec& spec, BayerPattern pattern, const ChromaFixed& k);
  // Full Bayer sampling: windows are rectified from `plane`, the frame's
  // packed samples (the table's layout, bayer_full.h), and scored with the
  // grid's `forms` (view_stretch.h). Both must outlive this object.
  void usePlane(const uint32_t* plane, const GradientForms& forms);
  int maxSide() const { return spec_.max_side; }
  struct Thresholds {
    float raw_low = 0;     // raw score of a weak peak (weak threshold x energy floor)
    float raw_strong = 0;  // raw score of a blob (threshold x energy floor)
    float low = 0;         // ratio of a weak peak
  };
  // The peaks in `region` (at most max_side cells a side) where mask != 0
  // (the full grid's peak mask), raw score above th.raw_low (and above
  // th.raw_strong unless `near` has a blob close by) and ratio above th.low,
  // appended to out[0, capacity). Returns how many.
  int peaks(const cv::Mat& raw, float gain, const CellRect& region, const uint8_t* mask, const Thresholds& th,
            const BlobSpacing& near, FinePeakFound* out, int capacity);
  // The fast-ball pass of this grid near cell `c`: sizes the scratch for
  // this grid's streak footprint `w` and a search `reach` lattice cells
  // either side of c's lattice cell. `lattice_mask`: the grid's
  // streakPeakMask.
  void configureStreaks(const StreakWindows& w, const uint8_t* lattice_mask, int reach);
  // The streak lattice peaks findStreakPeakRows finds on the whole grid
  // whose lattice cell lies within the reach of c's, scored as
  // streakScoreRows scores them at `levels` from chroma rectified here (the
  // same chroma, so the same scores), each placed by refineStreak. Appended
  // to out[0, capacity); returns how many.
  struct Streak {
    StreakPeak peak;  // the whole grid's lattice cell
    int orientation = 0;
    GridPx at;
  };
  int streaks(const cv::Mat& raw, float gain, const StreakLevels& levels, GridPx c, Streak* out, int capacity);

 private:
  // Chroma of window cells [x0, x0 + w) x [y0, y0 + h) into ca_, cb_ (row
  // stride w); false where its samples do not fit the box.
  bool rectify(const cv::Mat& raw, float gain, int x0, int y0, int w, int h);
  // Scratch for windows up to `side` cells a side.
  void reserve(int side);
  const GradientForms* windowForms(int x0, int y0, int w, int h);
  // Whether every block under cells [x0, x1) x [y0, y1) is plain.
  bool plainOver(int x0, int y0, int x1, int y1) const;

  const RemapTable* table_ = nullptr;
  FinePeakSpec spec_;
  BayerPattern pattern_ = BayerPattern::RGGB;
  ChromaFixed k_{};
  int n_ = 0;  // largest window side (cells)
  std::vector<uint32_t> box_, ring_;
  std::vector<int32_t> index_;
  std::vector<float> ca_, cb_, score_;
  // Full Bayer sampling: the frame's samples, the grid's forms and the
  // window's share of them (its origin on a block corner).
  const uint32_t* plane_ = nullptr;
  const GradientForms* forms_ = nullptr;
  GradientForms window_forms_;
  // The streak search: the grid's footprint and mask, and the patch's.
  StreakWindows streak_, patch_;
  const uint8_t* lattice_mask_ = nullptr;
  int reach_ = 0, side_ = 0;  // lattice cells: search reach, patch side
  std::vector<float> patch_coarse_, patch_score_;
  std::vector<uint8_t> patch_orient_, patch_mask_;
  std::vector<StreakPeak> patch_peaks_;
};

}  // namespace dv

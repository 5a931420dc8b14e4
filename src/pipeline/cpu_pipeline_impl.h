#pragma once
// The CPU pipeline's state and stages (cpu_pipeline.h), shared by the files
// that hold them: cpu_pipeline.cpp (set-up, the frame, whole-plane passes,
// fast balls, colors), cpu_band_pass.cpp (the banded pass: score and peaks
// band by band), cpu_coarse_search.cpp (peaks on a grid of twice the
// spacing, the full grid scored around them). Private to those files.
#include "pipeline/cpu_pipeline.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"
#include "pipeline/band_plan.h"
#include "pipeline/bayer_full.h"
#include "pipeline/bayer_sampling.h"
#include "pipeline/bayer_subsample.h"
#include "pipeline/blob_color_gate.h"
#include "pipeline/blob_spacing.h"
#include "pipeline/fine_peak.h"
#include "pipeline/kernels.h"
#include "pipeline/mosaic_binning.h"
#include "pipeline/band_peaks.h"
#include "pipeline/peak_select.h"
#include "pipeline/remap_table.h"
#include "pipeline/score_windows.h"
#include "pipeline/streak_markings.h"
#include "pipeline/streak_score.h"
#include "pipeline/thread_pool.h"
#include "pipeline/view_stretch.h"

namespace dv {
namespace cpu_pipeline_detail {

inline double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace cpu_pipeline_detail

struct CpuPipeline::Impl {
  CameraModel camera;
  PipelineOptions opt;
  RectifiedGrid grid;
  ThreadPool pool;
  RemapTable table;
  // The table the rectification reads through: `table`, or its transposed
  // form with the chroma samples stored transposed, when grid rows run along
  // image columns (reading down image columns misses the cache every cell).
  RemapTable table_t;
  bool transposed = false;
  const RemapTable& readTable() const { return transposed ? table_t : table; }
  ChromaTransform chroma;
  int sample_step = 2;   // full pixels per RGBX sample
  bool full_bayer = false;  // a sample per pixel of the mosaic (bayer_full.h)
  std::string sampling_note;
  int image_w = 0, image_h = 0;
  double gradient_scale = 1;  // cells
  int quadrant_r = 1;         // cells
  int inner_q = 0;            // cells, inner corner left out of each quadrant
  double circle_r = 1;        // cells
  int margin = 1;             // cells without a full score window
  double color_radius = 1;    // cells
  GradientForms forms;        // whitened gradient where the view stretches blobs (view_stretch.h)

  std::vector<uint32_t> packed;  // chroma samples, int16 pairs (not for banded frames)
  // Bayer 2x2 subsampling with the quadrant score: from the mosaic to the
  // score band by band (band_plan.h).
  bool banded = false;
  BandPlan bands;
  std::vector<double> band_bayer_ms;
  ChromaFixed chroma_fixed{};
  cv::Mat last_raw;  // header of the last frame, for colors and inspection
  std::vector<float> ca, cb, score;
  std::vector<int32_t> gdot;
  std::vector<uint32_t> sat;
  std::vector<uint8_t> peak_mask;  // 1 where a side blob's disc is seen (score_windows.h, peakMask)
  std::vector<std::vector<PeakCandidate>> candidates;  // one per pool part
  std::vector<int> candidate_counts;
  std::vector<PeakCandidate> merged;
  BlobSpacing spacing;
  // Weak peaks: the blobs they are looked for around, sorted by row, and
  // the same blobs indexed by place.
  std::vector<GridPx> near;
  BlobSpacing reach;
  ExpectedPlaces expected;  // weak peaks count near these too (blob.h)
  std::vector<std::vector<std::pair<int, int>>> spans;  // scratch of findPeaksNear, per part
  // Peaks found inside the banded pass (band_peaks.h), one list set per band;
  // the weak peaks around the blobs taken from them, and their ratios.
  std::vector<BandPeaks> band_peaks;
  std::vector<Blob> merged_blobs;  // per entry of `merged`, from the bands
  std::vector<int> rank;           // `merged` strongest first, as indices
  float luma_mean = 100;
  StreakLevels streak_levels;  // this frame's, from its marker contrast (streak_windows.h)
  bool has_frame = false;

  // Fast-ball pass (streak_score.h): coarse chroma pairs, score, best
  // orientation, peak mask, candidates per pool part.
  StreakWindows streak;
  std::vector<float> streak_coarse, streak_score;
  std::vector<uint8_t> streak_orient, streak_mask;
  MarkingMask streak_markings;  // grid cells on a field line (streak_markings.h)
  std::vector<MarkedStreak> streak_later;  // streak candidates on a marking (reserved)
  std::vector<std::vector<StreakPeak>> streak_candidates;
  std::vector<int> streak_counts;
  std::vector<StreakPeak> streak_merged;

  // Coarse search (pipeline_options.h): the pipeline of the binned mosaic
  // on a grid of twice the spacing, the binned mosaic, per pool part the
  // window that scores a region of this grid and the peaks it found.
  std::unique_ptr<Impl> coarse;
  cv::Mat binned;
  std::vector<FinePeak> fine_peaks;
  std::vector<CellRect> regions;                         // of this grid, around the coarse peaks
  std::vector<std::vector<FinePeakFound>> window_peaks;  // per pool part
  std::vector<int> window_counts;
  BlobSpacing coarse_reach;  // weak reach around the coarse pass's blobs, on this grid
  std::vector<FinePeakFound> found_peaks;
  // The coarse pass's fast-ball candidates (this grid's cells), the full
  // grid's found near them per pool part, and all of those.
  std::vector<GridPx> streak_centers;
  std::vector<std::vector<FinePeak::Streak>> part_streaks;
  std::vector<FinePeak::Streak> fine_streaks;
  // The coarse pass keeps every fast-ball candidate, blob or not: its blobs
  // may not survive the full grid's score, whose blobs then decide.
  bool streaks_unhidden = false;

  StageTimes times;
  std::string error;
  BlobColorGate color_gate;  // which peaks are colored enough (blob_color_gate.h)
  std::vector<std::array<float, 3>> found_rgb;  // per strong found peak (coarse search)

  Impl(const CameraModel& cam, const FieldModel& field, const PipelineOptions& o,
       const RectifiedGrid* fixed_grid = nullptr);

  // The coarse pass: its pipeline on the grid of twice the spacing, whose
  // cells cover 2x2 cells of this one. `binned`: on the mosaic binned to
  // half size, seen by the camera at half the image size (each pixel a 2x2
  // cell of the full image; pixel centers at integer coordinates). Else
  // (full Bayer sampling, a camera that sees far) on the frame itself, a
  // sample per pixel as here: its samples are then this grid's too.
  void makeCoarse(const FieldModel& field, const ScoreWindows& w, bool binned_mosaic);

  // The coarse search's frame: bin, find peaks on the coarse grid, score
  // this grid in regions around them and select its peaks.
  bool coarseProcess(const cv::Mat& raw, BlobList& out);

  // What the inspection views show: the pass that found the blobs, its
  // view brought onto this grid (cells repeated, the padding cut off).
  const Impl& shown() const { return coarse ? *coarse : *this; }
  cv::Mat onGrid(const cv::Mat& view) const {
    if (!coarse) return view;
    const int pad = static_cast<int>(std::lround((grid.x0 + 0.5 * grid.scale - coarse->grid.x0) / coarse->grid.scale));
    cv::Mat up;
    cv::resize(view(cv::Rect(pad, pad, (grid.width + 1) / 2, (grid.height + 1) / 2)), up, {}, 2, 2, cv::INTER_NEAREST);
    return up(cv::Rect(0, 0, grid.width, grid.height)).clone();
  }

  int weakCapacity() const { return opt.weak_threshold > 0 ? std::max(0, opt.max_weak_blobs) : 0; }

  // Splits rows [0, n) into one contiguous band per pool part and tells the
  // body its part index.
  template <class F>
  void forParts(int n, F&& body) {
    const int parts = pool.size();
    pool.parallelFor(parts, [&](int pb, int pe) {
      for (int p = pb; p < pe; ++p) {
        const int b = static_cast<int>(static_cast<long>(n) * p / parts);
        const int e = static_cast<int>(static_cast<long>(n) * (p + 1) / parts);
        body(p, b, e);
      }
    });
  }

  // Each stage over the whole frame in turn (full Bayer sampling, BGR
  // frames, the circle score).
  void wholePlaneScore(const cv::Mat& raw, bool bayer, float gain);

  // Rows [lo, hi) of one band's chroma: its own rows in the planes, the
  // others in a private buffer; rectified from the band's sample box when
  // first asked for.
  class BandRows;

  // Cells within this many rows of a peak are read by its ratio test
  // (energy window plus the gradient's reach).
  int energyReach() const { return ratioWindow() + static_cast<int>(std::floor(gradient_scale)) + 1; }
  int ratioWindow() const {
    return opt.score == BlobScoreKind::CircleMin ? static_cast<int>(std::lround(circle_r)) : quadrant_r;
  }
  // Raw score a peak must exceed to be a candidate: ratio > t needs
  // score > t * floor.
  float rawThreshold() const { return static_cast<float>(opt.threshold) * kEnergyFloor; }
  float lowThreshold() const {
    const float threshold = static_cast<float>(opt.threshold);
    return weakCapacity() > 0 ? std::min(threshold, static_cast<float>(opt.weak_threshold)) : threshold;
  }
  // A candidate's score over the gradient energy of its window (the energy
  // sum may stop once the ratio is known to be at most `low`).
  float peakRatio(const PeakCandidate& c, float low) const {
    return c.score / (windowEnergy(c.x, c.y, c.score / low) + kEnergyFloor);
  }
  // Gradient energy of the ratio window at (x, y), whitened where the view
  // stretches blobs (view_stretch.h); the sum may stop once above `stop`.
  float windowEnergy(int x, int y, float stop) const {
    return forms.plainAt(x, y) ? windowGradientEnergy(ca.data(), cb.data(), grid.width, gradient_scale, x, y,
                                                      ratioWindow(), stop)
                               : windowGradientEnergyForm(ca.data(), cb.data(), grid.width, gradient_scale, x, y,
                                                          ratioWindow(), forms.block(x, y) + 3, stop);
  }

  // Peaks of a band's inner rows (band_peaks.h): row y - 1 once row y has
  // its score. The ratio test runs at once where the energy window lies in
  // the band's own rows, which are in the planes and rectified already.
  class BandPeakRows;

  // After the banded pass: band c's first and last rows and the ratios its
  // pass could not compute.
  void finishBandPeaks(int c);

  // The blob of the peak at cell (x, y) with score `ratio`.
  Blob peakBlob(int x, int y, float ratio) const;

  // Weak peaks of band c (once the blobs are kept in `reach`): its
  // candidates near a blob, in list order, their ratio test and blobs.
  void bandWeakPeaks(int c, float low);

  // Bayer 2x2 subsampling, rectification and the quadrant score band by band
  // (band_plan.h): bit for bit the whole-plane stages. Peaks of the score
  // are looked for as it is made (band_peaks.h).
  void bandedScore(const cv::Mat& raw, float gain);

  bool checkFrame(const cv::Mat& raw);

  // Frame brightness for the exposure normalisation: a sparse sample (every
  // 16th row, every 4th cell), its rows shared out to the pool (integer
  // sums, the same in any order). The job also wakes the pool's workers
  // for the passes that follow.
  float frameLuma(const cv::Mat& raw, bool bayer);

  bool process(const cv::Mat& raw, BlobList& out);

  // Fast balls (streak_score.h): candidates the blob score missed, appended
  // after the blobs, strongest first (those on a marking last). The coarse
  // rows were made with the rectification; the lattice is scored here, at
  // the levels of this frame's marker contrast (known once the peaks are).
  void findStreaks(BlobList& out);

  // A fast-ball candidate at grid position g, its color from the frame.
  Blob streakBlob(GridPx g, float score) const;

  // Every blob the league uses is strongly colored; a near-neutral mean
  // color is a white line crossing or a gray feature, whose chroma edges
  // came from the carpet around it.
  bool saturated(const Blob& blob) const { return color_gate.colored(blob.rgb); }

  // Bilinear RGB of grid cell k from the last frame (co-sited samples).
  void sampleRgb(size_t k, float rgb[3]) const;

  void meanColor(GridPx g, float rgb[3]) const;
};

}  // namespace dv

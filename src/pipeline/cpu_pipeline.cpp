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
#include "pipeline/streak_score.h"
#include "pipeline/thread_pool.h"
#include "pipeline/view_stretch.h"

namespace dv {

namespace {

// Exposure normalisation: chroma is divided by the frame's mean brightness,
// so a darker or brighter exposure gives the same values. (Dividing by each
// cell's own brightness was tried: it lifts dark carpet against white lines
// until line crossings score like blobs.) Local differences in light (sun
// patches, shadows) are handled by the ratio score (score_windows.h).

// Bands per thread for the banded pass: a thread the OS delays holds up
// little of the frame, and the rows rectified twice stay few.
constexpr int kBandsPerThread = 4;
// At least this many bands, whatever the threads: at 2448x2048 a band's
// sample box is then about 1 MB at most (the level-2 cache of a core), where
// four bands on one thread made boxes of 1.9 MB that spilled to memory
// between the Bayer step and the rectification.
constexpr int kMinBands = 8;
// Blobs above which the weak-peak scan is shared out to the pool.
constexpr size_t kWeakScanOnPoolAbove = 150;
// Coarse search only where its grid stays this fine: on an 11.2 mm grid
// (1224 x 1024 subsampled from 4 m) every robot of the synthetic scenes is
// still found.
constexpr double kMaxCoarseGridMm = 12;
// The full grid is scored in regions around the coarse pass's peaks: each
// peak's square of kWindowReachMm, merged while they fit into
// kWindowSideMm a side. A robot's blobs make one region, which covers the
// whole pattern, so a side blob the coarse grid scored too low or merged
// with a neighbour is still found there.
constexpr double kWindowReachMm = 30;
constexpr double kWindowSideMm = 320;
// The coarse pass's thresholds, as a share of the full ones: the coarse
// grid scores peaks lower (faint discs about half), and the full grid's
// score decides. Weak peaks are looked for only near blobs, so their
// threshold can go lower at little cost.
constexpr double kCoarseThresholdFactor = 0.75;
constexpr double kCoarseWeakThresholdFactor = 0.5;
// The full grid's fast-ball pass runs on its streak lattice within this
// many lattice cells (22 mm each at 5.6 mm) of each coarse candidate. The
// candidate stands at its streak's centroid, but the full lattice peaks
// anywhere on the streak's score plateau, which spans the streak's length
// less the footprint's inner run: up to about +-40 mm for the longest
// streaks the footprint takes (a ball at 8 m/s, 107 mm; a far ball seen
// from the touch line, stretched along the view to 4 diameters). The two
// lattices are offset too, and a candidate's centroid may be pulled toward
// a colored neighbour (a ball against a robot). At one cell, the side
// view's ball 5.5 m away was lost: its coarse candidate lay 21 and 30 mm
// from the full lattice's two peaks, on cells two apart.
constexpr int kStreakSearchReach = 2;
constexpr int kStreakPeaksPerSearch = (2 * kStreakSearchReach + 1) * (2 * kStreakSearchReach + 1);
// A coarse candidate this close to a full-grid blob is that blob (its
// full-grid peaks would lie within kStreakBlobDistanceMm of it).
constexpr double kStreakCandidateAtBlobMm = 10;

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

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
  std::vector<std::vector<std::pair<int, int>>> spans;  // scratch of findPeaksNear, per part
  // Peaks found inside the banded pass (band_peaks.h), one list set per band;
  // the weak peaks around the blobs taken from them, and their ratios.
  std::vector<BandPeaks> band_peaks;
  std::vector<Blob> merged_blobs;  // per entry of `merged`, from the bands
  std::vector<int> rank;           // `merged` strongest first, as indices
  float luma_mean = 100;
  bool has_frame = false;

  // Fast-ball pass (streak_score.h): coarse chroma pairs, score, best
  // orientation, peak mask, candidates per pool part.
  StreakWindows streak;
  std::vector<float> streak_coarse, streak_score;
  std::vector<uint8_t> streak_orient, streak_mask;
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
       const RectifiedGrid* fixed_grid = nullptr)
      : camera(cam), opt(o), pool(o.threads), color_gate(cam, field) {
    const auto& c = camera.calibration();
    image_w = static_cast<int>(c.image_width);
    image_h = static_cast<int>(c.image_height);
    const BayerSamplingChoice sampling = chooseBayerSampling(camera, field, opt);
    opt.bayer_sampling = sampling.mode;
    sampling_note = sampling.describe();
    full_bayer = opt.bayer != BayerPattern::None && sampling.mode == BayerSampling::Full;
    const SampleLattice lattice = sampleLattice(opt);
    sample_step = lattice.step;
    grid = fixed_grid ? *fixed_grid : checkedGrid(camera, field, opt);
    chroma = ChromaTransform::of(opt.color);
    const ScoreWindows w = scoreWindows(grid.scale, opt.score);
    gradient_scale = w.gradient_scale;
    quadrant_r = w.quadrant_radius;
    circle_r = w.circle_radius;
    inner_q = w.inner_corner;
    margin = w.margin;
    color_radius = w.color_radius;

    table.build(camera, grid, opt.plane_height, lattice, pool);
    transposed = !full_bayer && sample_step == 2 && table.runsAlongColumns();
    // A stride of 4 KiB would put every column of the transposed store into
    // the same cache set: pad it off the power of two.
    const int stride_t = (table.src_height + 15) / 16 * 16 + 16;
    if (transposed) table_t = table.transposed(stride_t);

    const size_t cells = static_cast<size_t>(grid.width) * grid.height;
    banded = opt.bayer != BayerPattern::None && !full_bayer && opt.score != BlobScoreKind::CircleMin;
    if (banded) {
      // A few bands per thread, so that a thread the OS delays holds up
      // little; each band rectifies 2 * reach rows twice.
      const int reach = quadrant_r + static_cast<int>(std::floor(gradient_scale)) + 1;
      bands = BandPlan::build(readTable(), transposed, std::max(kMinBands, kBandsPerThread * pool.size()),
                              reach);
      band_bayer_ms.assign(bands.bands.size(), 0);
    } else {
      packed.assign(static_cast<size_t>(table.src_width) * (transposed ? stride_t : table.src_height), 0);
    }
    for (int c = 0; c < 3; ++c) {
      chroma_fixed.a[c] = static_cast<int>(std::lround(chroma.a[c] * 1024));
      chroma_fixed.b[c] = static_cast<int>(std::lround(chroma.b[c] * 1024));
    }
    ca.assign(cells, 0);
    cb.assign(cells, 0);
    score.assign(cells, 0);
    gdot.assign(cells, 0);
    sat.assign(static_cast<size_t>(grid.width + 1) * (grid.height + 1), 0);

    peak_mask = peakMask(table.valid, grid.width, grid.height, w);
    forms = gradientForms(camera, grid, opt.plane_height);

    // A streak peak counts only where its whole footprint is seen.
    streak = streakWindows(grid.scale, grid.width, grid.height);
    {
      streak_mask = streakPeakMask(table.valid.data(), grid.width, grid.height, streak);
      const size_t coarse = static_cast<size_t>(streak.coarse_width) * streak.coarse_height;
      const size_t lattice = streak_mask.size();
      streak_coarse.assign(2 * coarse, 0);
      streak_score.assign(lattice, 0);
      streak_orient.assign(lattice, 0);
    }

    const int parts = pool.size();
    streak_candidates.assign(parts, std::vector<StreakPeak>(kMaxStreakCandidates));
    streak_counts.assign(parts, 0);
    streak_merged.reserve(static_cast<size_t>(kMaxStreakCandidates) * parts);
    // Room for candidates that the ratio test removes afterwards.
    const int capacity = 4 * std::max(16, opt.max_blobs + weakCapacity());
    candidates.assign(parts, std::vector<PeakCandidate>(capacity));
    candidate_counts.assign(parts, 0);
    merged.reserve(static_cast<size_t>(capacity) * parts);
    spacing.configure(grid.width, grid.height, kMinBlobDistanceMm / grid.scale,
                      std::max(0, opt.max_blobs) + weakCapacity());
    reach.configure(grid.width, grid.height, w.weak_reach, std::max(0, opt.max_blobs));
    near.reserve(std::max(0, opt.max_blobs));
    spans.assign(parts, {});
    for (auto& v : spans) v.reserve(256);
    if (banded) {
      // A band holding more blobs than a frame may keep is left to the
      // plane scan.
      const int blob_room = std::max(16, opt.max_blobs + weakCapacity());
      band_peaks.assign(bands.bands.size(), {});
      for (BandPeaks& b : band_peaks) b.reserve(capacity, grid.width, blob_room);
      merged_blobs.reserve(static_cast<size_t>(blob_room) * bands.bands.size());
      rank.reserve(static_cast<size_t>(blob_room) * bands.bands.size());
      merged.reserve(static_cast<size_t>(blob_room) * bands.bands.size());
    }
    if (opt.coarse_search && 2 * grid.scale <= kMaxCoarseGridMm) {
      if (banded && !forms.any && image_w % 4 == 0 && image_h % 4 == 0) makeCoarse(field, w, /*binned=*/true);
      else if (full_bayer && opt.score == BlobScoreKind::QuadrantMin) makeCoarse(field, w, /*binned=*/false);
    }
  }

  // The coarse pass: its pipeline on the grid of twice the spacing, whose
  // cells cover 2x2 cells of this one. `binned`: on the mosaic binned to
  // half size, seen by the camera at half the image size (each pixel a 2x2
  // cell of the full image; pixel centers at integer coordinates). Else
  // (full Bayer sampling, a camera that sees far) on the frame itself, a
  // sample per pixel as here: its samples are then this grid's too.
  void makeCoarse(const FieldModel& field, const ScoreWindows& w, bool binned_mosaic) {
    CameraCalibration c = camera.calibration();
    if (binned_mosaic) {
      c.focal_length *= 0.5;
      c.principal_point_x = (c.principal_point_x - 0.5) * 0.5;
      c.principal_point_y = (c.principal_point_y - 0.5) * 0.5;
      c.image_width /= 2;
      c.image_height /= 2;
    }
    // Padded by the coarse score's margin on every side: cells without a
    // full score window are then outside this grid, so blobs are found as
    // close to its edges as here (cells outside the image are never peaks).
    RectifiedGrid g;
    g.scale = 2 * grid.scale;
    const int pad = scoreWindows(g.scale, opt.score).margin;
    g.width = (grid.width + 1) / 2 + 2 * pad;
    g.height = (grid.height + 1) / 2 + 2 * pad;
    g.x0 = grid.x0 + 0.5 * grid.scale - pad * g.scale;
    g.y0 = grid.y0 - 0.5 * grid.scale + pad * g.scale;
    PipelineOptions co = opt;
    co.coarse_search = false;
    co.bayer_sampling = binned_mosaic ? BayerSampling::Subsample : BayerSampling::Full;
    // Peaks a little below the thresholds too: the full grid's score decides.
    co.threshold *= kCoarseThresholdFactor;
    co.weak_threshold *= kCoarseWeakThresholdFactor;
    coarse = std::make_unique<Impl>(CameraModel(c), field, co, &g);
    coarse->streaks_unhidden = true;
    char note[128];
    std::snprintf(note, sizeof note, "; coarse search: peaks found on a %.1f mm grid, the %.1f mm grid scored around them",
                  g.scale, grid.scale);
    sampling_note += note;
    if (binned_mosaic) {
      binned.create(image_h / 2, image_w / 2, CV_8UC1);
    } else {
      // The coarse pass makes the samples this grid reads too.
      RemapTable& ct = coarse->table;
      ct.x_begin = std::min(ct.x_begin, table.x_begin), ct.x_end = std::max(ct.x_end, table.x_end);
      ct.y_begin = std::min(ct.y_begin, table.y_begin), ct.y_end = std::max(ct.y_end, table.y_end);
      packed.clear();
      packed.shrink_to_fit();
    }
    FinePeakSpec spec;
    spec.max_side = static_cast<int>(std::ceil(kWindowSideMm / grid.scale));
    spec.margin = w.margin;
    spec.gradient_scale = gradient_scale;
    spec.quadrant_r = quadrant_r;
    spec.inner_q = inner_q;
    spec.energy_r = w.energy_window;
    const size_t room = static_cast<size_t>(std::max(0, opt.max_blobs) + weakCapacity()) + kMaxStreakCandidates;
    regions.reserve(room);
    coarse_reach.configure(grid.width, grid.height, w.weak_reach, std::max(0, opt.max_blobs) + kMaxStreakCandidates);
    window_peaks.assign(pool.size(), std::vector<FinePeakFound>(room));
    window_counts.assign(pool.size(), 0);
    found_peaks.reserve(room * pool.size());
    fine_peaks.assign(pool.size(), {});
    for (FinePeak& f : fine_peaks) {
      f.configure(table, spec, opt.bayer, chroma_fixed);
      if (!binned_mosaic) f.usePlane(coarse->packed.data(), forms);
      f.configureStreaks(streak, streak_mask.data(), kStreakSearchReach);
    }
    const size_t coarse_streaks = static_cast<size_t>(kMaxStreakCandidates) * coarse->pool.size();
    streak_centers.reserve(coarse_streaks);
    part_streaks.assign(pool.size(), {});
    for (auto& list : part_streaks) list.reserve(coarse_streaks * kStreakPeaksPerSearch);
    fine_streaks.reserve(coarse_streaks * kStreakPeaksPerSearch);
  }

  // The coarse search's frame: bin, find peaks on the coarse grid, score
  // this grid in regions around them and select its peaks.
  bool coarseProcess(const cv::Mat& raw, BlobList& out) {
    const auto t_start = std::chrono::steady_clock::now();
    if (!binned.empty()) pool.parallelFor(image_h / 4, [&](int b, int e) { binMosaicRows(raw, binned, b, e); });
    const double bin_ms = msSince(t_start);
    if (!coarse->process(binned.empty() ? raw : binned, out)) {
      error = coarse->error;
      return false;
    }
    const auto t0 = std::chrono::steady_clock::now();
    last_raw = raw;
    luma_mean = coarse->luma_mean;
    color_gate.adoptNeutral(coarse->color_gate);
    // Regions of this grid around the coarse pass's peaks: each peak's
    // square of kWindowReachMm joins a region it overlaps while that stays
    // within the largest window (a robot's blobs make one region), else
    // starts one.
    regions.clear();
    const int r = static_cast<int>(std::ceil(kWindowReachMm / grid.scale));
    const int max_side = fine_peaks[0].maxSide();
    auto join = [&](const CellRect& a, const CellRect& b, CellRect& u) {
      if (a.x1 <= b.x0 || b.x1 <= a.x0 || a.y1 <= b.y0 || b.y1 <= a.y0) return false;
      u = {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
      return u.x1 - u.x0 <= max_side && u.y1 - u.y0 <= max_side;
    };
    auto addPeak = [&](const Blob& b) {
      const GridPx g = grid.toGrid(b.position);
      const int x = static_cast<int>(std::floor(g.x)), y = static_cast<int>(std::floor(g.y));
      const CellRect box{x - r, y - r, x + r + 2, y + r + 2};
      CellRect u;
      for (CellRect& reg : regions)
        if (join(reg, box, u)) {
          reg = u;
          return;
        }
      regions.push_back(box);
    };
    // Weak peaks are scored only near the coarse pass's blobs (the full
    // pass: near its own blobs).
    coarse_reach.clear();
    for (const Blob& b : out.blobs)
      if (!b.streak) {
        addPeak(b);
        const GridPx g = grid.toGrid(b.position);
        coarse_reach.keep(g.x, g.y);
      }
    for (const Blob& b : out.weak) addPeak(b);
    // Regions that grew into each other since: merged where they fit.
    for (size_t i = 0; i < regions.size(); ++i)
      for (size_t j = i + 1; j < regions.size();) {
        CellRect u;
        if (join(regions[i], regions[j], u)) {
          regions[i] = u;
          regions[j] = regions.back();
          regions.pop_back();
          j = i + 1;
        } else {
          ++j;
        }
      }
    const float threshold = static_cast<float>(opt.threshold), low = lowThreshold();
    const FinePeak::Thresholds th{low * kEnergyFloor, rawThreshold(), low};
    const float gain = 1.0f / (luma_mean * kPackedChromaScale);
    forParts(static_cast<int>(regions.size()), [&](int p, int b, int e) {
      std::vector<FinePeakFound>& list = window_peaks[p];
      int n = 0;
      for (int i = b; i < e; ++i)
        n += fine_peaks[p].peaks(raw, gain, regions[i], peak_mask.data(), th, coarse_reach, list.data() + n,
                                 static_cast<int>(list.size()) - n);
      window_counts[p] = n;
    });
    found_peaks.clear();
    for (size_t p = 0; p < window_peaks.size(); ++p)
      found_peaks.insert(found_peaks.end(), window_peaks[p].begin(), window_peaks[p].begin() + window_counts[p]);
    // Strongest first; a peak two windows found twice is the same cell.
    std::sort(found_peaks.begin(), found_peaks.end(), [](const FinePeakFound& a, const FinePeakFound& b) {
      return a.ratio != b.ratio ? a.ratio > b.ratio : (a.y != b.y ? a.y < b.y : a.x < b.x);
    });
    // Selected as the full pass selects its peaks: strongest first, one per
    // object, weak peaks only within reach of a blob.
    spacing.clear();
    reach.clear();
    // The coarse pass's fast-ball candidates, kept for after the blobs.
    streak_centers.clear();
    for (const Blob& b : out.blobs)
      if (b.streak) streak_centers.push_back(grid.toGrid(b.position));
    out.blobs.clear();
    out.weak.clear();
    // The frame's saturation scale from its strong peaks (blob_color_gate.h).
    found_rgb.clear();
    color_gate.beginPeaks();
    for (const FinePeakFound& f : found_peaks) {
      if (!(f.ratio > threshold)) break;  // strongest first
      found_rgb.emplace_back();
      meanColor(f.at, found_rgb.back().data());
      color_gate.addPeak(found_rgb.back().data());
    }
    color_gate.endPeaks();
    for (size_t i = 0; i < found_peaks.size(); ++i) {
      const FinePeakFound& f = found_peaks[i];
      const bool strong = f.ratio > threshold;
      if (spacing.nearKept(f.x, f.y)) continue;
      if (strong ? static_cast<int>(out.blobs.size()) >= opt.max_blobs
                 : static_cast<int>(out.weak.size()) >= weakCapacity() || !reach.nearKept(f.x, f.y))
        continue;
      Blob b;
      b.grid = f.at;
      b.position = grid.toField(f.at);
      b.score = f.ratio;
      if (strong) {
        std::copy(found_rgb[i].begin(), found_rgb[i].end(), b.rgb);
      } else {
        meanColor(b.grid, b.rgb);
      }
      if (!saturated(b)) continue;
      (strong ? out.blobs : out.weak).push_back(b);
      if (strong) reach.keep(b.grid.x, b.grid.y);
      spacing.keep(b.grid.x, b.grid.y);
    }
    // Fast balls: the full pass's streak lattice peaks near the coarse
    // candidates, then taken as the full pass takes them: strongest first,
    // where no blob is.
    forParts(static_cast<int>(streak_centers.size()), [&](int p, int b, int e) {
      std::vector<FinePeak::Streak>& list = part_streaks[p];
      list.clear();
      for (int i = b; i < e; ++i) {
        const GridPx c = streak_centers[i];
        if (nearBlob(out.blobs, c, grid.scale, kStreakCandidateAtBlobMm)) continue;
        const size_t n = list.size();
        list.resize(n + kStreakPeaksPerSearch);
        list.resize(n + fine_peaks[p].streaks(raw, gain, c, list.data() + n, kStreakPeaksPerSearch));
      }
    });
    fine_streaks.clear();
    for (const std::vector<FinePeak::Streak>& list : part_streaks)
      fine_streaks.insert(fine_streaks.end(), list.begin(), list.end());
    std::sort(fine_streaks.begin(), fine_streaks.end(),
              [](const FinePeak::Streak& a, const FinePeak::Streak& b) { return strongerStreak(a.peak, b.peak); });
    // A peak two searches found twice is the same lattice cell.
    fine_streaks.erase(std::unique(fine_streaks.begin(), fine_streaks.end(),
                                   [](const FinePeak::Streak& a, const FinePeak::Streak& b) {
                                     return a.peak.x == b.peak.x && a.peak.y == b.peak.y;
                                   }),
                       fine_streaks.end());
    for (const FinePeak::Streak& s : fine_streaks) {
      if (nearBlob(out.blobs, streakPeakCenter(streak, s.peak), grid.scale)) continue;
      const Blob b = streakBlob(s.at, s.peak.score);
      if (acceptStreakBlob(out.blobs, b, grid.scale, color_gate)) out.blobs.push_back(b);
    }
    out.neutral = color_gate.neutral();
    out.min_saturation = color_gate.threshold();
    times = coarse->times;
    times.bayer_ms += bin_ms;
    times.peaks_ms += msSince(t0);
    times.total_ms = msSince(t_start);
    has_frame = true;
    return true;
  }

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
  // body its part index (`here`: all parts in turn on this thread).
  template <class F>
  void forParts(int n, F&& body, bool here = false) {
    const int parts = pool.size();
    if (here) {
      for (int p = 0; p < parts; ++p)
        body(p, static_cast<int>(static_cast<long>(n) * p / parts), static_cast<int>(static_cast<long>(n) * (p + 1) / parts));
      return;
    }
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
  void wholePlaneScore(const cv::Mat& raw, bool bayer, float gain) {
    auto t0 = std::chrono::steady_clock::now();
    const int gw = grid.width, gh = grid.height;
    // Only the part of the image the grid reads.
    const int rows = table.y_end - table.y_begin;
    const int y0 = table.y_begin, x0 = table.x_begin, x1 = table.x_end;
    if (full_bayer) {
      pool.parallelFor(rows, [&](int b, int e) {
        fullBayerChromaRows(raw, opt.bayer, chroma_fixed, packed.data(), y0 + b, y0 + e, x0, x1);
      });
    } else if (bayer) {
      pool.parallelFor(rows, [&](int b, int e) {
        if (transposed)
          bayerChromaRowsTransposed(raw, opt.bayer, chroma_fixed, packed.data(), table_t.src_width, y0 + b,
                                    y0 + e, x0, x1);
        else
          bayerChromaRows(raw, opt.bayer, chroma_fixed, packed.data(), y0 + b, y0 + e, x0, x1);
      });
    } else {
      pool.parallelFor(rows, [&](int b, int e) {
        bgrChromaRows(raw, chroma_fixed, packed.data(), y0 + b, y0 + e, x0, x1);
      });
    }
    last_raw = raw;
    times.bayer_ms = msSince(t0);

    t0 = std::chrono::steady_clock::now();
    // The fast-ball pass's coarse rows are made from grid rows just
    // rectified, while they are in cache (streak_score.h).
    const int f = streak.factor, ch = streak.coarse_height;
    pool.parallelFor(gh, [&](int b, int e) {
      constexpr int kRows = 16;
      for (int y = b; y < e; y += kRows) {
        const int ye = std::min(e, y + kRows);
        rectifyChromaRows(readTable(), packed.data(), gain, ca.data(), cb.data(), y, ye);
        streakCoarseRows(ca.data(), cb.data(), gw, streak, streak_coarse.data(), std::min(ch, (y + f - 1) / f),
                         std::min(ch, (ye + f - 1) / f));
      }
    });
    times.rectify_ms = msSince(t0);

    // The circle score reads G and its row prefix sums from whole planes;
    // the quadrant score makes its G and table rows itself, band by band
    // (their time is in score_ms).
    const bool circle = opt.score == BlobScoreKind::CircleMin;
    t0 = std::chrono::steady_clock::now();
    if (circle) {
      pool.parallelFor(gh, [&](int b, int e) {
        gradientDotRows(ca.data(), cb.data(), gw, gh, gradient_scale, gdot.data(), b, e);
      });
    }
    times.gradient_ms = msSince(t0);

    t0 = std::chrono::steady_clock::now();
    if (circle)
      pool.parallelFor(gh, [&](int b, int e) { satRowPrefixRows(gdot.data(), gw, gh, sat.data(), b, e); });
    times.sat_ms = msSince(t0);

    t0 = std::chrono::steady_clock::now();
    if (circle) {
      pool.parallelFor(gh, [&](int b, int e) {
        circleMinScoreRows(sat.data(), gw, gh, circle_r, score.data(), b, e);
      });
    } else {
      pool.parallelFor(gh, [&](int b, int e) {
        thread_local std::vector<uint32_t> ring;  // column sums of the band, reused
        quadrantMinScoreFromChroma(ca.data(), cb.data(), gw, gh, gradient_scale, quadrant_r, inner_q,
                                   score.data(), b, e, ring, &forms);
      });
    }
    times.score_ms = msSince(t0);
  }

  // Rows [lo, hi) of one band's chroma: its own rows in the planes, the
  // others in a private buffer; rectified from the band's sample box when
  // first asked for.
  class BandRows final : public ChromaRowSource {
   public:
    BandRows(Impl& m, const BandPlan::Band& band, const uint32_t* box, float gain, float* halo_a,
             float* halo_b)
        : m_(m), band_(band), box_(box), gain_(gain), halo_a_(halo_a), halo_b_(halo_b), done_(band.lo) {}
    void rows(int y, const float*& a, const float*& b) override {
      if (y >= done_) makeUpTo(y + 1);
      float *pa, *pb;
      rowPointers(y, pa, pb);
      a = pa, b = pb;
    }
    void makeUpTo(int y_end) {
      const size_t w = static_cast<size_t>(m_.grid.width);
      const RemapTable& t = m_.readTable();
      for (; done_ < y_end; ++done_) {
        float *a, *b;
        rowPointers(done_, a, b);
        rectifyChromaCells(m_.bands.index.data() + band_.index_offset + (done_ - band_.lo) * w,
                           t.frac.data() + done_ * w, band_.stride, box_, gain_, a, b, w);
        // The fast-ball pass's coarse row that reads this own row, while it
        // is in cache (each own row belongs to one band, so each is made once).
        const int f = m_.streak.factor, c = done_ / f;
        if (done_ % f == 0 && done_ >= band_.y_begin && done_ < band_.y_end && c < m_.streak.coarse_height)
          streakCoarseRows(m_.ca.data(), m_.cb.data(), m_.grid.width, m_.streak, m_.streak_coarse.data(), c,
                           c + 1);
      }
    }

   private:
    void rowPointers(int y, float*& a, float*& b) const {
      const size_t w = static_cast<size_t>(m_.grid.width);
      if (y >= band_.y_begin && y < band_.y_end) {
        a = m_.ca.data() + y * w;
        b = m_.cb.data() + y * w;
        return;
      }
      const size_t slot = y < band_.y_begin ? y - band_.lo : (band_.y_begin - band_.lo) + (y - band_.y_end);
      a = halo_a_ + slot * w;
      b = halo_b_ + slot * w;
    }
    Impl& m_;
    const BandPlan::Band& band_;
    const uint32_t* box_;
    float gain_;
    float *halo_a_, *halo_b_;
    int done_;
  };

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
  class BandPeakRows final : public ScoreRowSink {
   public:
    BandPeakRows(Impl& m, const BandPlan::Band& band, BandPeaks& out)
        : m_(m), band_(band), out_(out), low_(m.lowThreshold() * kEnergyFloor), raw_(m.rawThreshold()),
          threshold_(static_cast<float>(m.opt.threshold)), reach_(m.energyReach()) {}
    void rowDone(int y) override {
      const int t = y - 1;
      if (t <= band_.y_begin) return;  // the first row is left for after the pass
      BandPeaks::List& l = out_.inner;
      const int from = out_.scanRow(l, m_.score.data(), m_.peak_mask.data(), m_.grid.width, m_.grid.height,
                                    m_.margin, low_, t);
      if (t - reach_ < band_.y_begin || t + reach_ >= band_.y_end) return;
      for (int i = from; i < l.n; ++i)
        if (l.peaks[i].score > raw_) l.ratio[i] = m_.peakRatio(l.peaks[i], threshold_);
    }

   private:
    Impl& m_;
    const BandPlan::Band& band_;
    BandPeaks& out_;
    float low_, raw_, threshold_;
    int reach_;
  };

  // After the banded pass: band c's first and last rows and the ratios its
  // pass could not compute.
  void finishBandPeaks(int c) {
    const BandPlan::Band& band = bands.bands[c];
    BandPeaks& bp = band_peaks[c];
    const float low = lowThreshold() * kEnergyFloor, raw = rawThreshold();
    const float threshold = static_cast<float>(opt.threshold);
    if (band.y_end == band.y_begin) return;  // an empty band (a grid of few rows)
    bp.scanRow(bp.first, score.data(), peak_mask.data(), grid.width, grid.height, margin, low, band.y_begin);
    if (band.y_end - 1 > band.y_begin)
      bp.scanRow(bp.last, score.data(), peak_mask.data(), grid.width, grid.height, margin, low, band.y_end - 1);
    for (BandPeaks::List* l : {&bp.first, &bp.inner, &bp.last})
      for (int i = 0; i < l->n; ++i) {
        const PeakCandidate& c = l->peaks[i];
        if (!(c.score > raw)) continue;
        if (l->ratio[i] == BandPeaks::kRatioPending) l->ratio[i] = peakRatio(c, threshold);
        if (!(l->ratio[i] > threshold)) continue;
        if (bp.blob_n == static_cast<int>(bp.blobs.size())) {
          bp.full = true;
          return;
        }
        bp.blob_cells[bp.blob_n] = {c.x, c.y, l->ratio[i]};
        bp.blobs[bp.blob_n++] = peakBlob(c.x, c.y, l->ratio[i]);
      }
  }

  // The blob of the peak at cell (x, y) with score `ratio`.
  Blob peakBlob(int x, int y, float ratio) const {
    Blob blob;
    blob.grid = interpolatePeak(score.data(), grid.width, x, y);
    blob.position = grid.toField(blob.grid);
    blob.score = ratio;
    meanColor(blob.grid, blob.rgb);
    return blob;
  }

  // Weak peaks of band c (once the blobs are kept in `reach`): its
  // candidates near a blob, in list order, their ratio test and blobs.
  void bandWeakPeaks(int c, float low) {
    BandPeaks& bp = band_peaks[c];
    const float raw_low = low * kEnergyFloor, threshold = static_cast<float>(opt.threshold);
    for (const BandPeaks::List* l : {&bp.first, &bp.inner, &bp.last})
      for (int i = 0; i < l->n; ++i) {
        const PeakCandidate& p = l->peaks[i];
        if (!(p.score > raw_low) || !reach.nearKept(p.x, p.y)) continue;
        ++bp.weak_raw;
        const float ratio = peakRatio(p, low);
        if (!(ratio > low && ratio <= threshold)) continue;
        if (bp.weak_n == static_cast<int>(bp.weak.size())) {
          bp.full = true;
          return;
        }
        bp.weak_cells[bp.weak_n] = {p.x, p.y, ratio};
        bp.weak[bp.weak_n++] = peakBlob(p.x, p.y, ratio);
      }
  }

  // Bayer 2x2 subsampling, rectification and the quadrant score band by band
  // (band_plan.h): bit for bit the whole-plane stages. Peaks of the score
  // are looked for as it is made (band_peaks.h).
  void bandedScore(const cv::Mat& raw, float gain) {
    const int gw = grid.width, gh = grid.height;
    pool.parallelFor(static_cast<int>(bands.bands.size()), [&](int first, int last) {
      // Per thread, sized on the first frame.
      thread_local std::vector<uint32_t> box_store, ring;
      thread_local std::vector<float> halo;
      box_store.resize(bands.box_size + 16);
      halo.resize(2 * static_cast<size_t>(bands.haloRows()) * gw);
      // Whole 64-byte lines for the box rows (its stride is a multiple of 16).
      uint32_t* box = box_store.data();
      while (reinterpret_cast<uintptr_t>(box) % 64) ++box;
      for (int c = first; c < last; ++c) {
        const BandPlan::Band& band = bands.bands[c];
        const auto t0 = std::chrono::steady_clock::now();
        bayerChromaBox(raw, opt.bayer, chroma_fixed, transposed, box, band.stride, band.i_begin, band.i_end,
                       band.j_begin, band.j_end);
        band_bayer_ms[c] = msSince(t0);
        BandRows rows(*this, band, box, gain, halo.data(), halo.data() + static_cast<size_t>(bands.haloRows()) * gw);
        band_peaks[c].clear();
        BandPeakRows peaks(*this, band, band_peaks[c]);
        quadrantMinScoreFromRows(rows, gw, gh, gradient_scale, quadrant_r, inner_q, score.data(), band.y_begin,
                                 band.y_end, ring, &forms, &peaks);
        rows.makeUpTo(band.y_end);  // own rows the score did not need (next to the plane's edges)
      }
    });
  }

  bool checkFrame(const cv::Mat& raw) {
    if (raw.empty()) {
      error = "empty frame";
      return false;
    }
    if (raw.cols != image_w || raw.rows != image_h) {
      error = "frame is " + std::to_string(raw.cols) + "x" + std::to_string(raw.rows) +
              ", calibration expects " + std::to_string(image_w) + "x" + std::to_string(image_h);
      return false;
    }
    if (raw.depth() != CV_8U || (raw.channels() != 1 && raw.channels() != 3)) {
      error = "frame type must be 8-bit Bayer (1 channel) or 8-bit BGR (3 channels)";
      return false;
    }
    if (raw.channels() == 1 && opt.bayer == BayerPattern::None) {
      error = "1-channel frame but the Bayer pattern is 'none'";
      return false;
    }
    return true;
  }

  // Frame brightness for the exposure normalisation: a sparse sample (every
  // 16th row, every 4th cell), its rows shared out to the pool (integer
  // sums, the same in any order). The job also wakes the pool's workers
  // for the passes that follow.
  float frameLuma(const cv::Mat& raw, bool bayer) {
    // Bayer: over the 2x2 cells under the samples read (fullBayerCells).
    const SampleRegion read{table.x_begin, table.x_end, table.y_begin, table.y_end};
    const SampleRegion cells = full_bayer ? fullBayerCells(read) : read;
    constexpr int kRowStep = 16;
    std::atomic<uint64_t> total_sum{0}, total_n{0};
    const int rows = (cells.y_end - cells.y_begin + kRowStep - 1) / kRowStep;
    pool.parallelFor(rows, [&](int rb, int re) {
      uint64_t sum = 0, n = 0;
      for (int j = rb; j < re; ++j) {
        const int y = cells.y_begin + j * kRowStep;
        if (bayer) {
          // R + B + mean of the two greens, per 2x2 cell.
          const auto s = bayerSites(opt.bayer);
          const uint8_t* r0 = raw.ptr<uint8_t>(2 * y);
          const uint8_t* r1 = raw.ptr<uint8_t>(2 * y + 1);
          const uint8_t* rr = s.ry ? r1 : r0;
          const uint8_t* br = s.by ? r1 : r0;
          for (int x = cells.x_begin; x < cells.x_end; x += 4) {
            const int all = r0[2 * x] + r0[2 * x + 1] + r1[2 * x] + r1[2 * x + 1];
            const int r = rr[2 * x + s.rx], b = br[2 * x + s.bx];
            sum += 2 * (r + b) + (all - r - b);
            n += 6;
          }
        } else {
          const uint8_t* row = raw.ptr<uint8_t>(y);
          for (int x = table.x_begin; x < table.x_end; x += 4)
            sum += row[3 * x] + row[3 * x + 1] + row[3 * x + 2], n += 3;
        }
      }
      total_sum.fetch_add(sum, std::memory_order_relaxed);
      total_n.fetch_add(n, std::memory_order_relaxed);
    });
    return static_cast<float>(total_sum.load()) / std::max<uint64_t>(1, total_n.load()) + 1.0f;
  }

  bool process(const cv::Mat& raw, BlobList& out) {
    out.blobs.clear();
    out.weak.clear();
    out.plane_height = opt.plane_height;
    if (!checkFrame(raw)) return false;
    const bool bayer = raw.channels() == 1;
    if (bayer != (opt.bayer != BayerPattern::None)) {
      // A BGR frame for a Bayer-configured camera: the sample grid differs.
      error = bayer ? "Bayer frame for a BGR camera" : "BGR frame for a camera configured as Bayer";
      return false;
    }
    error.clear();
    if (coarse) return coarseProcess(raw, out);
    color_gate.measureNeutral(raw, opt.bayer);
    out.neutral = color_gate.neutral();
    const auto t_start = std::chrono::steady_clock::now();
    auto t0 = t_start;

    luma_mean = frameLuma(raw, bayer);
    times.color_ms = msSince(t0);

    const float gain = 1.0f / (luma_mean * kPackedChromaScale);
    if (banded) {
      t0 = std::chrono::steady_clock::now();
      bandedScore(raw, gain);
      last_raw = raw;
      // Bayer time as its share of the threads' time; rectification and the
      // score run interleaved and are reported together as the score.
      const double wall = msSince(t0);
      double bayer_sum = 0;
      for (double v : band_bayer_ms) bayer_sum += v;
      times.bayer_ms = std::min(wall, bayer_sum / pool.size());
      times.rectify_ms = 0;
      times.gradient_ms = times.sat_ms = 0;
      times.score_ms = wall - times.bayer_ms;
    } else {
      wholePlaneScore(raw, bayer, gain);
    }

    t0 = std::chrono::steady_clock::now();
    const int gw = grid.width, gh = grid.height;
    const float threshold = static_cast<float>(opt.threshold);
    // Keeps the candidates of list[0, n) whose ratio exceeds `low` and (for
    // weak peaks) does not exceed `high`, with the ratio as their score.
    auto ratioTest = [&](PeakCandidate* list, int n, float low, float high) {
      int kept = 0;
      for (int i = 0; i < n; ++i) {
        // Energy above score / low fails the ratio test (the floor only
        // lowers the ratio further), so its sum may stop there.
        const float energy = windowEnergy(list[i].x, list[i].y, list[i].score / low);
        const float ratio = list[i].score / (energy + kEnergyFloor);
        if (ratio > low && ratio <= high) list[kept++] = {list[i].x, list[i].y, ratio};
      }
      return kept;
    };
    const auto by_score = [](const PeakCandidate& a, const PeakCandidate& b) { return a.score > b.score; };
    // `merged`, the `cap` strongest first.
    auto strongestFirst = [&](size_t cap) {
      const size_t keep = std::min(merged.size(), cap);
      std::partial_sort(merged.begin(), merged.begin() + keep, merged.end(), by_score);
      return keep;
    };
    // The candidates of all parts, the `cap` strongest first.
    auto gather = [&](size_t cap) {
      merged.clear();
      for (size_t p = 0; p < candidates.size(); ++p)
        merged.insert(merged.end(), candidates[p].begin(), candidates[p].begin() + candidate_counts[p]);
      return strongestFirst(cap);
    };
    // One blob per object: a weaker peak within kMinBlobDistanceMm of a
    // stronger one is a second maximum of the same blob. Real blobs are at
    // least ~43 mm apart (two touching balls).
    auto select = [&](size_t keep, std::vector<Blob>& list, size_t max_size) {
      for (size_t i = 0; i < keep && list.size() < max_size; ++i) {
        const PeakCandidate& c = merged[i];
        if (spacing.nearKept(c.x, c.y)) continue;
        Blob blob;
        blob.grid = interpolatePeak(score.data(), gw, c.x, c.y);
        blob.position = grid.toField(blob.grid);
        blob.score = c.score;
        meanColor(blob.grid, blob.rgb);
        if (!saturated(blob)) continue;
        list.push_back(blob);
        spacing.keep(blob.grid.x, blob.grid.y);
      }
    };

    // Banded frames: the peaks the pass found, finished on the pool together
    // with the fast-ball score (which needs only the coarse rows the pass
    // made). Their lists in band order are the scan's in row order.
    const size_t capacity = candidates[0].size();
    bool from_bands = banded;
    if (banded) {
      const int nb = static_cast<int>(bands.bands.size());
      const int lh = streak.lattice_height, ns = std::min(lh, nb);
      pool.parallelFor(nb + ns, [&](int b, int e) {
        for (int i = b; i < e; ++i) {
          if (i < nb) {
            finishBandPeaks(i);
          } else {
            const int s = i - nb;
            streakScoreRows(streak_coarse.data(), streak, streak_score.data(), streak_orient.data(),
                            static_cast<int>(static_cast<long>(lh) * s / ns),
                            static_cast<int>(static_cast<long>(lh) * (s + 1) / ns));
          }
        }
      });
      // The scan keeps at most `capacity` candidates per part, before the
      // ratio test; past that (or a band list full), scan the plane as
      // before, which is exact in every case.
      const float raw = rawThreshold();
      size_t strong = 0;
      merged.clear();
      merged_blobs.clear();
      for (const BandPeaks& bp : band_peaks) {
        from_bands = from_bands && !bp.full;
        merged.insert(merged.end(), bp.blob_cells.begin(), bp.blob_cells.begin() + bp.blob_n);
        merged_blobs.insert(merged_blobs.end(), bp.blobs.begin(), bp.blobs.begin() + bp.blob_n);
        for (const BandPeaks::List* l : {&bp.first, &bp.inner, &bp.last})
          for (int i = 0; i < l->n; ++i) strong += l->peaks[i].score > raw;
      }
      from_bands = from_bands && strong <= capacity;
    }
    if (!from_bands) {
      forParts(gh, [&](int p, int b, int e) {
        auto& list = candidates[p];
        // Raw score > threshold * floor is necessary for ratio > threshold.
        const int n = findPeakRows(score.data(), peak_mask.data(), gw, gh, margin, threshold * kEnergyFloor,
                                   list.data(), 0, static_cast<int>(list.size()), b, e);
        candidate_counts[p] = ratioTest(list.data(), n, threshold, std::numeric_limits<float>::infinity());
      });
    }
    spacing.clear();
    const size_t max_blobs = std::max(0, opt.max_blobs);
    // select() for candidates whose blobs are made: `merged` and
    // `merged_blobs` side by side, taken in the order partial_sort gives
    // `merged` (it compares scores only), sorting indices.
    auto selectMade = [&](size_t cap, std::vector<Blob>& list, size_t max_size) {
      rank.resize(merged.size());
      for (size_t i = 0; i < rank.size(); ++i) rank[i] = static_cast<int>(i);
      const size_t keep = std::min(rank.size(), cap);
      std::partial_sort(rank.begin(), rank.begin() + keep, rank.end(),
                        [&](int a, int b) { return merged[a].score > merged[b].score; });
      for (size_t i = 0; i < keep && list.size() < max_size; ++i) {
        const Blob& blob = merged_blobs[rank[i]];
        if (spacing.nearKept(merged[rank[i]].x, merged[rank[i]].y) || !saturated(blob)) continue;
        list.push_back(blob);
        spacing.keep(blob.grid.x, blob.grid.y);
      }
    };
    // The frame's saturation scale from its strong peaks (blob_color_gate.h).
    color_gate.beginPeaks();
    if (from_bands) {
      for (const Blob& b : merged_blobs) color_gate.addPeak(b.rgb);
      color_gate.endPeaks();
      selectMade(max_blobs, out.blobs, std::numeric_limits<size_t>::max());
    } else {
      const size_t keep = gather(max_blobs);
      for (size_t i = 0; i < keep; ++i) {
        float rgb[3];
        meanColor(interpolatePeak(score.data(), gw, merged[i].x, merged[i].y), rgb);
        color_gate.addPeak(rgb);
      }
      color_gate.endPeaks();
      select(keep, out.blobs, std::numeric_limits<size_t>::max());
    }
    out.min_saturation = color_gate.threshold();

    // Weak peaks only around the blobs (hysteresis): where a side blob of a
    // robot whose center blob was found may lie.
    if (weakCapacity() > 0 && !out.blobs.empty()) {
      const float low = std::min(threshold, static_cast<float>(opt.weak_threshold));
      near.clear();
      reach.clear();
      for (const Blob& b : out.blobs) near.push_back(b.grid), reach.keep(b.grid.x, b.grid.y);
      std::sort(near.begin(), near.end(), [](const GridPx& a, const GridPx& b) { return a.y < b.y; });
      // Few blobs: on this thread, as their discs are a small part of the
      // grid (less work than waking the pool again); many (noisy carpet):
      // band by band on the pool.
      auto weakRows = [&](int p, int b, int e) {
        auto& list = candidates[p];
        const int n = findPeaksNear(score.data(), peak_mask.data(), gw, gh, margin, low * kEnergyFloor,
                                    near.data(), static_cast<int>(near.size()), reach, spans[p], list.data(), 0,
                                    static_cast<int>(list.size()), b, e);
        candidate_counts[p] = ratioTest(list.data(), n, low, threshold);
      };
      // Up to max_weak_blobs weak peaks, strongest first (second maxima of
      // blobs do not count).
      const size_t all = std::numeric_limits<size_t>::max();
      const size_t max_weak = static_cast<size_t>(weakCapacity());
      // From the bands' lists, band by band on the pool: their peaks near a
      // blob, in row order, are what findPeaksNear finds while there are no
      // more than a part's capacity.
      bool weak_from_bands = from_bands;
      if (weak_from_bands) {
        pool.parallelFor(static_cast<int>(band_peaks.size()), [&](int b, int e) {
          for (int c = b; c < e; ++c) bandWeakPeaks(c, low);
        });
        size_t raw_n = 0;
        merged.clear();
        merged_blobs.clear();
        for (const BandPeaks& bp : band_peaks) {
          raw_n += bp.weak_raw;
          weak_from_bands = weak_from_bands && !bp.full;
          merged.insert(merged.end(), bp.weak_cells.begin(), bp.weak_cells.begin() + bp.weak_n);
          merged_blobs.insert(merged_blobs.end(), bp.weak.begin(), bp.weak.begin() + bp.weak_n);
        }
        weak_from_bands = weak_from_bands && raw_n <= capacity;
      }
      if (weak_from_bands) {
        selectMade(all, out.weak, max_weak);
      } else {
        std::fill(candidate_counts.begin(), candidate_counts.end(), 0);
        if (near.size() <= kWeakScanOnPoolAbove) weakRows(0, 0, gh);
        else forParts(gh, weakRows);
        select(gather(all), out.weak, max_weak);
      }
    }
    times.peaks_ms = msSince(t0);

    t0 = std::chrono::steady_clock::now();
    findStreaks(out, /*scored=*/banded);
    times.streak_ms = msSince(t0);
    times.total_ms = msSince(t_start);
    has_frame = true;
    return true;
  }

  // Fast balls (streak_score.h): candidates the blob score missed, appended
  // after the blobs, strongest first. The coarse rows were made with the
  // rectification; `scored`: the lattice score too (the banded path makes
  // it on the pool beside the peaks).
  void findStreaks(BlobList& out, bool scored) {
    const int lh = streak.lattice_height;
    if (!scored) {
      pool.parallelFor(lh, [&](int b, int e) {
        streakScoreRows(streak_coarse.data(), streak, streak_score.data(), streak_orient.data(), b, e);
      });
    }
    auto peaks = [&](int p, int b, int e) {
      streak_counts[p] = findStreakPeakRows(streak_score.data(), streak_mask.data(), streak,
                                            streak_candidates[p].data(), 0, kMaxStreakCandidates, b, e);
    };
    // The lattice is small: on this thread when the pool would only be woken
    // for it (the same parts, so the same candidates).
    if (scored) forParts(lh, peaks, /*here=*/true);
    else forParts(lh, peaks);
    streak_merged.clear();
    for (size_t p = 0; p < streak_candidates.size(); ++p)
      streak_merged.insert(streak_merged.end(), streak_candidates[p].begin(),
                           streak_candidates[p].begin() + streak_counts[p]);
    std::sort(streak_merged.begin(), streak_merged.end(), strongerStreak);
    for (const StreakPeak& p : streak_merged) {
      if (!streaks_unhidden && nearBlob(out.blobs, streakPeakCenter(streak, p), grid.scale)) continue;
      const int o = streak_orient[static_cast<size_t>(p.y) * streak.lattice_width + p.x];
      const Blob blob = streakBlob(
          refineStreak(ca.data(), cb.data(), grid.width, grid.height, streak_coarse.data(), streak, p, o), p.score);
      if (streaks_unhidden || acceptStreakBlob(out.blobs, blob, grid.scale, color_gate)) out.blobs.push_back(blob);
    }
  }

  // A fast-ball candidate at grid position g, its color from the frame.
  Blob streakBlob(GridPx g, float score) const {
    Blob blob;
    blob.grid = g;
    blob.position = grid.toField(g);
    blob.score = score;
    blob.streak = true;
    meanColor(blob.grid, blob.rgb);
    return blob;
  }

  // Every blob the league uses is strongly colored; a near-neutral mean
  // color is a white line crossing or a gray feature, whose chroma edges
  // came from the carpet around it.
  bool saturated(const Blob& blob) const { return color_gate.colored(blob.rgb); }

  // Bilinear RGB of grid cell k from the last frame (co-sited samples).
  void sampleRgb(size_t k, float rgb[3]) const {
    const int i = table.index[k];
    const int sx = i % table.src_width, sy = i / table.src_width;
    const float fx = (table.frac[k] & 255) / 256.0f, fy = (table.frac[k] >> 8) / 256.0f;
    float p[4][3];
    for (int n = 0; n < 4; ++n) {
      if (full_bayer) fullBayerRgbAt(last_raw, opt.bayer, sx + (n & 1), sy + (n >> 1), p[n]);
      else sampleRgbAt(last_raw, opt.bayer, sx + (n & 1), sy + (n >> 1), p[n]);
    }
    const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    for (int c = 0; c < 3; ++c) rgb[c] = w[0] * p[0][c] + w[1] * p[1][c] + w[2] * p[2][c] + w[3] * p[3][c];
  }

  void meanColor(GridPx g, float rgb[3]) const {
    const double r = color_radius;
    const int x0 = std::max(0, static_cast<int>(std::ceil(g.x - r)));
    const int x1 = std::min(grid.width - 1, static_cast<int>(std::floor(g.x + r)));
    const int y0 = std::max(0, static_cast<int>(std::ceil(g.y - r)));
    const int y1 = std::min(grid.height - 1, static_cast<int>(std::floor(g.y + r)));
    float sum[3] = {0, 0, 0};
    int n = 0;
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        if ((x - g.x) * (x - g.x) + (y - g.y) * (y - g.y) > r * r) continue;
        float c[3];
        sampleRgb(static_cast<size_t>(y) * grid.width + x, c);
        sum[0] += c[0], sum[1] += c[1], sum[2] += c[2];
        ++n;
      }
    }
    for (int c = 0; c < 3; ++c) rgb[c] = n ? sum[c] / n : 0;
  }
};

CpuPipeline::CpuPipeline(const CameraModel& camera, const FieldModel& field,
                         const PipelineOptions& opt)
    : impl_(std::make_unique<Impl>(camera, field, opt)) {}
CpuPipeline::~CpuPipeline() = default;
CpuPipeline::CpuPipeline(CpuPipeline&&) noexcept = default;
CpuPipeline& CpuPipeline::operator=(CpuPipeline&&) noexcept = default;

bool CpuPipeline::process(const cv::Mat& raw, BlobList& out) { return impl_->process(raw, out); }
const std::string& CpuPipeline::lastError() const { return impl_->error; }
const std::string& CpuPipeline::samplingNote() const { return impl_->sampling_note; }
const float* CpuPipeline::scoreData() const { return impl_->score.data(); }
const RectifiedGrid& CpuPipeline::grid() const { return impl_->grid; }
const StageTimes& CpuPipeline::times() const { return impl_->times; }
const PipelineOptions& CpuPipeline::options() const { return impl_->opt; }
double CpuPipeline::gradientScale() const { return impl_->gradient_scale; }
int CpuPipeline::quadrantRadius() const { return impl_->quadrant_r; }

std::optional<ImagePx> CpuPipeline::gridToImage(GridPx g) const {
  const FieldMm f = impl_->grid.toField(g);
  return impl_->camera.fieldToImage({f.x, f.y, impl_->opt.plane_height});
}

cv::Mat CpuPipeline::debugRectified() const {
  const auto& m = impl_->shown();
  cv::Mat out(m.grid.height, m.grid.width, CV_8UC3, cv::Scalar(0, 0, 0));
  if (!m.has_frame) return impl_->onGrid(out);
  for (int y = 0; y < out.rows; ++y) {
    auto* row = out.ptr<cv::Vec3b>(y);
    for (int x = 0; x < out.cols; ++x) {
      float c[3];
      m.sampleRgb(static_cast<size_t>(y) * out.cols + x, c);
      row[x] = cv::Vec3b(cv::saturate_cast<uint8_t>(c[2]), cv::saturate_cast<uint8_t>(c[1]),
                         cv::saturate_cast<uint8_t>(c[0]));
    }
  }
  return impl_->onGrid(out);
}

namespace {

// Signed plane -> gray with 0 at 128, +-full_scale at 255 / 0.
template <class T>
cv::Mat signedView(const T* data, int w, int h, double full_scale) {
  cv::Mat out(h, w, CV_8UC1);
  const double k = full_scale > 0 ? 127.0 / full_scale : 0;
  for (int y = 0; y < h; ++y) {
    auto* row = out.ptr<uint8_t>(y);
    for (int x = 0; x < w; ++x)
      row[x] = cv::saturate_cast<uint8_t>(128 + k * static_cast<double>(data[static_cast<size_t>(y) * w + x]));
  }
  return out;
}

}  // namespace

cv::Mat CpuPipeline::debugGradient() const {
  const auto& m = impl_->shown();
  // The quadrant score never writes G out: make it here (not a hot path).
  std::vector<int32_t> gdot(m.gdot.size(), 0);
  if (m.has_frame)
    gradientDotRows(m.ca.data(), m.cb.data(), m.grid.width, m.grid.height, m.gradient_scale, gdot.data(), 0,
                    m.grid.height);
  // Full scale at the 99.9th percentile of |G| so blobs stand out.
  std::vector<int32_t> mags;
  mags.reserve(gdot.size() / 7 + 1);
  for (size_t i = 0; i < gdot.size(); i += 7) mags.push_back(std::abs(gdot[i]));
  double full = 1;
  if (!mags.empty()) {
    auto it = mags.begin() + static_cast<long>(mags.size() * 0.999);
    std::nth_element(mags.begin(), it, mags.end());
    full = std::max(1, *it);
  }
  return impl_->onGrid(signedView(gdot.data(), m.grid.width, m.grid.height, full));
}

cv::Mat CpuPipeline::debugScore() const {
  const auto& m = impl_->shown();
  // The threshold maps to a quarter of the range above 0.
  return impl_->onGrid(signedView(m.score.data(), m.grid.width, m.grid.height, 4 * m.opt.threshold));
}

}  // namespace dv

// The coarse search (pipeline_options.h): peaks on the binned mosaic's grid
// of twice the spacing, this grid scored only in regions around them.
#include "pipeline/cpu_pipeline_impl.h"

namespace dv {

using cpu_pipeline_detail::msSince;

namespace {

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

}  // namespace

void CpuPipeline::Impl::makeCoarse(const FieldModel& field, const ScoreWindows& w, bool binned_mosaic) {
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
  coarse_reach.configure(grid.width, grid.height, w.weak_reach,
                         std::max(0, opt.max_blobs) + kMaxStreakCandidates + ExpectedPlaces::kMax);
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
  streak_later.reserve(fine_streaks.capacity());  // no-op where the full pass reserved more
}

bool CpuPipeline::Impl::coarseProcess(const cv::Mat& raw, BlobList& out) {
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
  auto addPeak = [&](const FieldMm& at) {
    const GridPx g = grid.toGrid(at);
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
  auto addReach = [&](const FieldMm& at) {
    addPeak(at);
    const GridPx g = grid.toGrid(at);
    coarse_reach.keep(g.x, g.y);
  };
  for (const Blob& b : out.blobs)
    if (!b.streak) addReach(b.position);
  for (int k = 0; k < expected.n; ++k) addReach(expected.at[k]);
  for (const Blob& b : out.weak) addPeak(b.position);
  for (const Blob& b : out.pale) addPeak(b.position);
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
  for (int k = 0; k < expected.n; ++k) {
    const GridPx g = grid.toGrid(expected.at[k]);
    reach.keep(g.x, g.y);
  }
  // The coarse pass's fast-ball candidates, kept for after the blobs.
  streak_centers.clear();
  for (const Blob& b : out.blobs)
    if (b.streak) streak_centers.push_back(grid.toGrid(b.position));
  out.clear();
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
  streak_levels = streakLevels(color_gate.markerContrast(), luma_mean);
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
    if (!saturated(b)) {
      if (strong) out.keepIfPale(b);
      continue;
    }
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
      list.resize(n + fine_peaks[p].streaks(raw, gain, streak_levels, c, list.data() + n, kStreakPeaksPerSearch));
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
  takeStreaksMarkingsLast(
      fine_streaks,
      [&](const FinePeak::Streak& s, Blob& b) {
        if (nearBlob(out.blobs, streakPeakCenter(streak, s.peak), grid.scale)) return false;
        b = streakBlob(s.at, s.peak.score);
        return true;
      },
      streak_markings, raw, opt.bayer, streak_levels, out.blobs, streak_later, grid.scale, color_gate);
  out.neutral = color_gate.neutral();
  out.carpet = color_gate.carpet();
  out.min_saturation = color_gate.threshold();
  times = coarse->times;
  times.bayer_ms += bin_ms;
  times.peaks_ms += msSince(t0);
  times.total_ms = msSince(t_start);
  has_frame = true;
  return true;
}

}  // namespace dv

#include "pipeline/cpu_pipeline_impl.h"

namespace dv {

using cpu_pipeline_detail::msSince;

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

}  // namespace

CpuPipeline::Impl::Impl(const CameraModel& cam, const FieldModel& field, const PipelineOptions& o,
                        const RectifiedGrid* fixed_grid)
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
  color_gate.setChroma(chroma);
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
    // The coarse search's own pass (a fixed grid) hands its streaks on
    // unhidden: only the full pass takes them past the markings.
    if (!fixed_grid) streak_markings = MarkingMask(camera, field, grid, opt.plane_height);
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
  streak_later.reserve(static_cast<size_t>(kMaxStreakCandidates) * parts);
  // Room for candidates that the ratio test removes afterwards.
  const int capacity = 4 * std::max(16, opt.max_blobs + weakCapacity());
  candidates.assign(parts, std::vector<PeakCandidate>(capacity));
  candidate_counts.assign(parts, 0);
  merged.reserve(static_cast<size_t>(capacity) * parts);
  spacing.configure(grid.width, grid.height, kMinBlobDistanceMm / grid.scale,
                    std::max(0, opt.max_blobs) + weakCapacity());
  reach.configure(grid.width, grid.height, w.weak_reach, std::max(0, opt.max_blobs) + ExpectedPlaces::kMax);
  near.reserve(std::max(0, opt.max_blobs) + ExpectedPlaces::kMax);
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

void CpuPipeline::Impl::wholePlaneScore(const cv::Mat& raw, bool bayer, float gain) {
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

bool CpuPipeline::Impl::checkFrame(const cv::Mat& raw) {
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

float CpuPipeline::Impl::frameLuma(const cv::Mat& raw, bool bayer) {
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

bool CpuPipeline::Impl::process(const cv::Mat& raw, BlobList& out) {
  out.clear();
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
  out.carpet = color_gate.carpet();
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
      if (!saturated(blob)) {
        if (&list == &out.blobs) out.keepIfPale(blob);
        continue;
      }
      list.push_back(blob);
      spacing.keep(blob.grid.x, blob.grid.y);
    }
  };

  // Banded frames: the peaks the pass found, finished on the pool. Their
  // lists in band order are the scan's in row order.
  const size_t capacity = candidates[0].size();
  bool from_bands = banded;
  if (banded) {
    pool.parallelFor(static_cast<int>(bands.bands.size()), [&](int b, int e) {
      for (int i = b; i < e; ++i) finishBandPeaks(i);
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
      if (spacing.nearKept(merged[rank[i]].x, merged[rank[i]].y)) continue;
      if (!saturated(blob)) {
        if (&list == &out.blobs) out.keepIfPale(blob);
        continue;
      }
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
  streak_levels = streakLevels(color_gate.markerContrast(), luma_mean);

  // Weak peaks only around the blobs (hysteresis): where a side blob of a
  // robot whose center blob was found may lie.
  if (weakCapacity() > 0 && (!out.blobs.empty() || expected.n > 0)) {
    const float low = std::min(threshold, static_cast<float>(opt.weak_threshold));
    near.clear();
    reach.clear();
    for (const Blob& b : out.blobs) near.push_back(b.grid), reach.keep(b.grid.x, b.grid.y);
    for (int k = 0; k < expected.n; ++k) {
      const GridPx g = grid.toGrid(expected.at[k]);
      near.push_back(g), reach.keep(g.x, g.y);
    }
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
  findStreaks(out);
  times.streak_ms = msSince(t0);
  times.total_ms = msSince(t_start);
  has_frame = true;
  return true;
}

void CpuPipeline::Impl::findStreaks(BlobList& out) {
  // Scored once the frame's peaks have given its marker contrast.
  const int lh = streak.lattice_height;
  pool.parallelFor(lh, [&](int b, int e) {
    streakScoreRows(streak_coarse.data(), streak, streak_levels, streak_score.data(), streak_orient.data(), b, e);
  });
  auto peaks = [&](int p, int b, int e) {
    streak_counts[p] = findStreakPeakRows(streak_score.data(), streak_mask.data(), streak,
                                          streak_candidates[p].data(), 0, kMaxStreakCandidates, b, e);
  };
  forParts(lh, peaks);
  streak_merged.clear();
  for (size_t p = 0; p < streak_candidates.size(); ++p)
    streak_merged.insert(streak_merged.end(), streak_candidates[p].begin(),
                         streak_candidates[p].begin() + streak_counts[p]);
  std::sort(streak_merged.begin(), streak_merged.end(), strongerStreak);
  auto refined = [&](const StreakPeak& p) {
    const int o = streak_orient[static_cast<size_t>(p.y) * streak.lattice_width + p.x];
    return streakBlob(
        refineStreak(ca.data(), cb.data(), grid.width, grid.height, streak_coarse.data(), streak, p, o), p.score);
  };
  if (streaks_unhidden) {
    for (const StreakPeak& p : streak_merged) out.blobs.push_back(refined(p));
    return;
  }
  takeStreaksMarkingsLast(
      streak_merged,
      [&](const StreakPeak& p, Blob& blob) {
        if (nearBlob(out.blobs, streakPeakCenter(streak, p), grid.scale)) return false;
        blob = refined(p);
        return true;
      },
      streak_markings, last_raw, opt.bayer, streak_levels, out.blobs, streak_later, grid.scale, color_gate);
}

Blob CpuPipeline::Impl::streakBlob(GridPx g, float score) const {
  Blob blob;
  blob.grid = g;
  blob.position = grid.toField(g);
  blob.score = score;
  blob.streak = true;
  meanColor(blob.grid, blob.rgb);
  return blob;
}

void CpuPipeline::Impl::sampleRgb(size_t k, float rgb[3]) const {
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

void CpuPipeline::Impl::meanColor(GridPx g, float rgb[3]) const {
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

CpuPipeline::CpuPipeline(const CameraModel& camera, const FieldModel& field,
                         const PipelineOptions& opt)
    : impl_(std::make_unique<Impl>(camera, field, opt)) {}
CpuPipeline::~CpuPipeline() = default;
CpuPipeline::CpuPipeline(CpuPipeline&&) noexcept = default;
CpuPipeline& CpuPipeline::operator=(CpuPipeline&&) noexcept = default;

bool CpuPipeline::process(const cv::Mat& raw, BlobList& out) { return impl_->process(raw, out); }
void CpuPipeline::expect(const ExpectedPlaces& places) {
  impl_->expected = places;
  if (impl_->coarse) impl_->coarse->expected = places;
}
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

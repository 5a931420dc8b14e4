#pragma once
// Options and per-stage timings of the pixel pipeline.

namespace dv {

enum class ColorSpace { DRGB, YUV };
enum class BayerPattern { None /* input is BGR 8UC3 */, RGGB, GRBG, GBRG, BGGR };
enum class BlobScoreKind { QuadrantMin, CircleMin };
// How a Bayer mosaic becomes color samples (see bayer_sampling.h):
//   Subsample  one sample per 2x2 cell (thesis 5.2.3), a quarter of the pixels;
//   Full       one sample per pixel (every 2x2 window, the same arithmetic);
//   Auto       Full where the camera's 2x2 cells are coarse on the field.
enum class BayerSampling { Auto, Subsample, Full };

struct PipelineOptions {
  ColorSpace color = ColorSpace::DRGB;
  BlobScoreKind score = BlobScoreKind::QuadrantMin;
  BayerPattern bayer = BayerPattern::RGGB;
  BayerSampling bayer_sampling = BayerSampling::Auto;
  double plane_height = 150;  // mm, rectification plane (max robot height)
  // Blob score threshold. Scores are ratios (weakest quadrant's mean gradient
  // dot product over the window's mean gradient energy plus a small floor, in
  // exposure-normalised chroma), so one value serves every exposure and light
  // level; low-resolution cameras are sampled at every pixel (bayer_sampling)
  // or resampled to a finer grid (kResampleAboveMm), so the windows are the
  // same in mm at 1224 x 1024 and 2448 x 2048. Measured on the synthetic
  // scenes seen from above (normal, uneven light, dark and noisy, blue white
  // balance, gray carpet, motion blur): at 2448 x 2048 side blobs score
  // 0.3..1; at 1224 x 1024 (blurrier blobs) mostly 0.25..0.7, a few below;
  // carpet texture and noise mostly below 0.2 (0.2 lets dark, noisy carpet
  // at 1224 x 1024 through; 0.21 with full sampling costs precision 0.97
  // there). Line crossings can score like blobs;
  // near-neutral blobs are dropped by color (see cpu_pipeline.cpp).
  double threshold = 0.24;
  int max_blobs = 2000;
  // Weak peaks (BlobList::weak): scores in (weak_threshold, threshold]. Far,
  // blurred or noisy side blobs land there, among many texture and noise
  // peaks, so they are handed over apart and used only where the pattern
  // vouches for them (detection/weak_sides.h). 0 turns them off. The
  // score goes with the square of the chroma, so a camera that halves the
  // saturation quarters it: under cold LED + saturation 0.4 + gamma 0.6 at
  // 1224 x 1024 side blobs score 0.06..0.12 (0.12 lost 5 of 88 robots
  // there, 0.06 two; 0.04 no better), and the whole sweep keeps precision
  // 1.000 at 0.06.
  double weak_threshold = 0.06;
  int max_weak_blobs = 1000;
  int threads = 0;  // 0 = all cores
  // Coarse search: where the grid is fine (a 2448 x 2048 camera from above:
  // 5.6 mm), peaks are looked for on a grid of twice the spacing (a quarter
  // of the cells; under 2x2 subsampling from the mosaic binned 2x2 cells at
  // a time, under full sampling from the same samples), and the full grid is
  // scored only in regions around them (fine_peak.h), whose peaks are the
  // blobs. The CPU pipeline only; false: the full grid everywhere.
  bool coarse_search = true;
};

// Wall time of each stage of the last frame, milliseconds. bayer_ms includes
// the chroma conversion (done on the subsampled samples, since it is linear);
// color_ms is only the frame brightness statistic; gradient_ms and sat_ms
// (row prefix) are whole-plane passes of the circle score only (the quadrant
// score makes its own G and table rows band by band, in score_ms); peaks_ms includes the ratio test, interpolation and blob colors;
// streak_ms is the fast-ball pass (streak_score.h) from its coarse chroma,
// made while the rectified rows are in cache.
// Where the CPU runs Bayer subsampling to score band by band (band_plan.h),
// bayer_ms is the Bayer part's share of that pass (its thread time over the
// threads), rectify_ms is 0 and score_ms is the rest of the pass, which
// also finds the peaks of the bands' inner rows and most ratio tests
// (band_peaks.h). The fast-ball lattice score is in streak_ms: it waits for
// the peaks, whose colors set its floor (streak_windows.h).
struct StageTimes {
  double bayer_ms = 0, rectify_ms = 0, color_ms = 0, gradient_ms = 0, sat_ms = 0, score_ms = 0,
         peaks_ms = 0, streak_ms = 0, total_ms = 0;
};

// Parses "rggb", "grbg", "gbrg", "bggr" or "none" (case-insensitive); false if unknown.
bool parseBayerPattern(const char* text, BayerPattern& out);
const char* bayerPatternName(BayerPattern p);
// Parses "auto", "subsample" or "full" (case-insensitive); false if unknown.
bool parseBayerSampling(const char* text, BayerSampling& out);
const char* bayerSamplingName(BayerSampling s);

}  // namespace dv

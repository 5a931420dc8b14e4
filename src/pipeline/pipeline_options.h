#pragma once
// Options and per-stage timings of the pixel pipeline.

namespace dv {

enum class ColorSpace { DRGB, YUV };
enum class BayerPattern { None /* input is BGR 8UC3 */, RGGB, GRBG, GBRG, BGGR };
enum class BlobScoreKind { QuadrantMin, CircleMin };

struct PipelineOptions {
  ColorSpace color = ColorSpace::DRGB;
  BlobScoreKind score = BlobScoreKind::QuadrantMin;
  BayerPattern bayer = BayerPattern::RGGB;
  double plane_height = 150;  // mm, rectification plane (max robot height)
  // Blob score threshold. Scores are ratios (weakest quadrant's mean gradient
  // dot product over the window's mean gradient energy plus a small floor, in
  // exposure-normalised chroma), so one value serves every exposure, light
  // level and resolution. Measured on the synthetic scenes seen from above
  // (normal, uneven light, dark and noisy, blue white balance, gray carpet,
  // motion blur): center blobs and balls 0.49..1.2, side blobs 0.28..1;
  // carpet texture and noise mostly below 0.3. Line crossings can score like
  // blobs; near-neutral blobs are dropped by color (see cpu_pipeline.cpp).
  double threshold = 0.28;
  int max_blobs = 2000;
  int threads = 0;  // 0 = all cores
};

// Wall time of each stage of the last frame, milliseconds. bayer_ms includes
// the chroma conversion (done on the subsampled samples, since it is linear);
// color_ms is only the frame brightness statistic; sat_ms is both prefix
// passes; peaks_ms includes the ratio test, interpolation and blob colors.
struct StageTimes {
  double bayer_ms = 0, rectify_ms = 0, color_ms = 0, gradient_ms = 0, sat_ms = 0, score_ms = 0,
         peaks_ms = 0, total_ms = 0;
};

// Parses "rggb", "grbg", "gbrg", "bggr" or "none" (case-insensitive); false if unknown.
bool parseBayerPattern(const char* text, BayerPattern& out);
const char* bayerPatternName(BayerPattern p);

}  // namespace dv

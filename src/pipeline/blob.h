#pragma once
// What the pixel pipeline hands to detection: blobs found on the rectified
// field grid of one camera frame.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/units.h"

namespace dv {

struct Blob {
  FieldMm position;  // field mm on the rectification plane (z = plane height)
  GridPx grid;       // sub-cell peak position on the rectified grid
  float score = 0;   // normalised blob score (dimensionless, higher = stronger)
  float rgb[3] = {0, 0, 0};  // mean color of the blob's disc, 0..255 per channel
  // Found by the fast-ball pass (streak_score.h), not by the blob score:
  // only ever a ball candidate, `score` is the streak score.
  bool streak = false;
};

// Mean channel level (0..255) from which a blob's channel counts as
// clipped: a saturated disc averages below 255 through its rim, blur and
// the sensor noise (the sweep's clipped ball at 1224 x 1024: 246).
inline constexpr float kClipLevel = 240.f;

// Clipped in two or three channels: over-exposed toward a pale yellow or
// white, whatever its color was.
inline bool clippedPale(const float rgb[3]) {
  return (rgb[0] >= kClipLevel) + (rgb[1] >= kClipLevel) + (rgb[2] >= kClipLevel) >= 2;
}

// The color of the field's white lines in one frame (pipeline/
// blob_color_gate.h), 0..255 per channel: the frame's neutral, from which
// the camera's color cast is read. Valid when enough line samples were seen.
struct NeutralColor {
  bool valid = false;
  float rgb[3] = {0, 0, 0};
  int samples = 0;  // line samples the estimate rests on
};

// The carpet beside the white lines in one frame (pipeline/blob_color_gate.h),
// 0..255 per channel, the median over the line samples: the field's color
// as this frame shows it. Valid where the lines were seen where the
// geometry puts them.
struct CarpetColor {
  bool valid = false;
  float rgb[3] = {0, 0, 0};
};

// Where the detector expects a faint object in the next frame: a fast
// ball's place on its course, on the rectification plane (field mm). A
// compressed stream can wash such a ball out to a weak peak; weak peaks
// there count as if near a blob (PixelPipeline::expect).
struct ExpectedPlaces {
  static constexpr int kMax = 4;
  FieldMm at[kMax];
  int n = 0;
};

// Blobs of one frame, strongest first. Capacity is reserved once per camera.
struct BlobList {
  double plane_height = 150;  // mm, the plane the grid lies on
  std::vector<Blob> blobs;  // score above PipelineOptions::threshold
  // Peaks scoring between PipelineOptions::weak_threshold and threshold,
  // strongest first, none within a blob's distance of a stronger one. Alone
  // they are mostly carpet texture and noise; the detector takes one only
  // where a robot pattern of strong blobs predicts a side blob.
  std::vector<Blob> weak;
  // Strong peaks the color gate dropped that clipped pale (clippedPale):
  // after the lines' white balance a ball in a sun patch, clipped to (245,
  // 250, 225) or (255, 254, 143), is as little saturated as a line
  // crossing. Only ever a ball candidate, judged by its shape and place
  // (detector_pale_balls.cpp); at most kMaxPale, strongest first.
  static constexpr size_t kMaxPale = 16;
  std::vector<Blob> pale;
  // Clears the lists (pale's room reserved once).
  void clear() {
    blobs.clear();
    weak.clear();
    if (pale.capacity() < kMaxPale) pale.reserve(kMaxPale);
    pale.clear();
  }
  // Keeps a strong peak the gate dropped where it clipped pale.
  void keepIfPale(const Blob& b) {
    if (pale.size() < kMaxPale && clippedPale(b.rgb)) pale.push_back(b);
  }
  NeutralColor neutral;
  CarpetColor carpet;
  // The saturation (max - min) / max, after the lines' white balance, a
  // blob needed in this frame (blob_color_gate.h).
  float min_saturation = 0;
};

}  // namespace dv

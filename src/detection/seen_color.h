#pragma once
// What the camera saw at a place where the robot pattern predicts a side
// blob that did not peak (at the image border, or far away where a dot is
// one or two pixels tall): the mean color of the frame over the part of a
// disc on the robot top that lies in the image. Read from the frame through
// the camera model, so both pixel backends give the same color and the
// footprint is where the camera saw the dot, not a disc on the rectified
// grid.
#include <opencv2/core.hpp>

#include "core/units.h"
#include "geometry/camera_model.h"
#include "pipeline/pipeline_options.h"

namespace dv {

// The frame a blob list came from: the raw Bayer mosaic (CV_8UC1, read with
// `bayer`) or the BGR image (CV_8UC3).
struct FrameView {
  const cv::Mat* image = nullptr;
  BayerPattern bayer = BayerPattern::RGGB;
};

struct SeenColor {
  float rgb[3] = {0, 0, 0};
  double share = 0;  // share of the disc inside the image, 0..1
};

// Co-sited RGB (0..255) at image position (u, v): bilinear between the
// 2x2 windows' samples around it (sample (x, y) describes pixel
// (x + 0.5, y + 0.5)); a BGR frame's nearest pixel. Clamped to the image.
void frameRgbAt(const FrameView& frame, double u, double v, float rgb[3]);

// Lattice points across the disc.
inline constexpr int kSeenColorSteps = 9;

// Mean RGB (0..255) over the lattice points of the disc of `radius` mm
// around `center` (on the plane z = center.z) that fall inside the image.
SeenColor seenDiscColor(const FrameView& frame, const CameraModel& camera, const FieldPoint& center,
                        double radius);

// Mean RGB over the lattice points of the image disc of `radius_px` around
// `center` that clip in no channel (kClipLevel); share: their share of the
// disc's points inside the image. An over-exposed blob's own color is
// where it did not clip: a ball's shaded rim.
SeenColor unclippedDiscColor(const FrameView& frame, ImagePx center, double radius_px);

}  // namespace dv

#pragma once
// Extrinsics and focal length from four or more known field points (thesis
// §5.1.8): the user gives their image positions; Ceres fits focal length,
// orientation and position with the distortion and principal point from the
// line-based intrinsic step held fixed. The camera height is fixed when given,
// as a camera looking straight down cannot observe it (§5.1.3).
#include <optional>
#include <string>
#include <vector>

#include "core/units.h"
#include "geometry/calibration/camera_params.h"
#include "geometry/calibration/intrinsics.h"

namespace dv {

struct PointCorrespondence {
  FieldPoint field;
  ImagePx image;
};

struct PointPoseOptions {
  std::optional<double> camera_height_mm;
  int image_width = 0, image_height = 0;
};

struct PointPoseResult {
  CameraParams params;
  double rms_px = 0;  // reprojection error over the points
};

// Why the points cannot fix a pose, or nullopt: a field point given twice,
// points bunched together in the image, or no four of them off one line
// (on the field or in the image). `width`/`height`: the image size.
std::optional<std::string> pointSetProblem(const std::vector<PointCorrespondence>& points, int width,
                                           int height);

// Empty when no start value converges in front of the camera.
std::optional<PointPoseResult> solvePointPose(const std::vector<PointCorrespondence>& points,
                                              const PixelDistortion& distortion,
                                              const PointPoseOptions& options);

// The four corners of a field rectangle in the order --corners takes them:
// counter-clockwise from the corner with the smallest x and y.
std::vector<FieldPoint> regionCornersCounterClockwise(double x_min, double x_max, double y_min,
                                                      double y_max);

}  // namespace dv

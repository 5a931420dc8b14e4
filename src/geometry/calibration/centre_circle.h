#pragma once
// The centre circle as a pose feature: its image is (close to) an ellipse,
// fitted to the curved line pixels that no straight line explains. With the
// halfway line through it, the circle's two crossings with that line and
// the tangents there fix three of the four points a homography needs; the
// fourth slides along the halfway line with the unknown image of the
// circle's centre, so a few positions are offered as hypotheses.
#include <optional>
#include <vector>

#include "geometry/calibration/calibrate_camera.h"
#include "geometry/calibration/image_lines.h"
#include "geometry/calibration/point_pose.h"

namespace dv {

struct ImageEllipse {
  cv::Point2d center;
  double a = 0, b = 0;  // semi-axes, px (a >= b)
  double angle = 0;     // direction of the a axis, rad
  int pixels = 0;
};

// In undistorted pixels; empty when no curved pixels fit one ellipse well.
std::optional<ImageEllipse> findCentreCircle(const LineObservation& obs, const PixelDistortion& distortion,
                                             const std::vector<ImageLine>& straight, int width, int height);

// Four-point sets (image in distorted pixels) from the ellipse and the image
// line that passes through its middle, for circle radius `radius_mm`; empty
// when no line does.
std::vector<std::vector<PointCorrespondence>> centreCircleHypotheses(const ImageEllipse& ellipse,
                                                                     const std::vector<ImageLine>& straight,
                                                                     const PixelDistortion& distortion,
                                                                     double radius_mm);

}  // namespace dv

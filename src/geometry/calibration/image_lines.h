#pragma once
// Straight field lines in the image, in undistorted pixels, as the automatic
// pose search uses them: fitted to a line group's pixels, crossed, compared.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "geometry/calibration/intrinsics.h"
#include "geometry/calibration/line_groups.h"

namespace dv {

// n . p = rho with n = (cos theta, sin theta).
struct ImageLine {
  double theta = 0, rho = 0;
  double extent = 0;
  cv::Point2d mid;
  double distanceTo(cv::Point2d p) const { return std::abs(std::cos(theta) * p.x + std::sin(theta) * p.y - rho); }
};

// Empty for short or curved groups (the centre circle's arcs).
std::optional<ImageLine> fitImageLine(const LineGroup& group, const PixelDistortion& distortion);

double directionDifference(const ImageLine& a, const ImageLine& b);  // rad, in [0, pi/2]
std::optional<cv::Point2d> intersect(const ImageLine& a, const ImageLine& b);
double signedArea(const std::vector<cv::Point2d>& polygon);

}  // namespace dv

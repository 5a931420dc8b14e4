#pragma once
// Radial distortion and principal point from straight field lines (thesis
// §5.1.7, after Thormählen): the line pixels of each long group must lie on a
// straight line once undistorted. Ceres (Levenberg-Marquardt) minimises their
// distances to their fitted lines with a robust loss.
//
// The distortion is estimated in pixel units, kappa = k / f^2, because the
// league's k is in normalised units and the focal length is not known yet:
// undistorted (px, relative to the principal point) = d (1 + kappa |d|^2).
// Converting with the focal length found later is exact, so no alternation
// between the intrinsic and extrinsic steps is needed for this model.
#include <optional>
#include <vector>

#include "core/units.h"
#include "geometry/calibration/line_groups.h"

namespace dv {

struct PixelDistortion {
  double kappa = 0;  // 1/px^2
  double cx = 0, cy = 0;  // principal point, px
  double k(double focal_length) const { return kappa * focal_length * focal_length; }
  ImagePx undistort(ImagePx p) const;
  // Inverse of undistort; empty beyond the reachable radius (kappa < 0).
  std::optional<ImagePx> distort(ImagePx undistorted) const;
};

struct IntrinsicsOptions {
  // Only groups at least this long (px); the thesis uses half the image height.
  double min_group_extent_px = 0;
  // Weak prior on the principal point around the image center (px, 1 sigma),
  // so that it stays put where the distortion does not observe it.
  double principal_point_sigma_px = 150;
  bool fit_principal_point = true;
};

struct IntrinsicsResult {
  PixelDistortion distortion;
  int groups_used = 0;
  double rms_px = 0;  // straightness residual after the fit
  double rms_before_px = 0;
};

// Empty when fewer than two long groups with pixels are given.
std::optional<IntrinsicsResult> calibrateDistortion(const std::vector<LineGroup>& groups,
                                                    int image_width, int image_height,
                                                    const IntrinsicsOptions& options);

}  // namespace dv

#pragma once
// Carpet shading: noise at several scales (large soft patches down to fibre
// clumps) on a field-space raster, the kind of random blob-like brightness
// variation a real carpet shows under a camera. Zero mean, unit deviation.
#include <cstdint>
#include <opencv2/core.hpp>

#include "geometry/field_model.h"

namespace dv {

class CarpetTexture {
 public:
  CarpetTexture() = default;
  // Covers `area` (field mm) with texels of `texel_mm`.
  CarpetTexture(const FieldRect& area, double texel_mm, uint64_t seed);

  // Bilinear sample at a field point; 0 outside the raster.
  float at(double x, double y) const {
    const double fx = (x - x0_) * inv_texel_, fy = (y - y0_) * inv_texel_;
    const int ix = int(fx), iy = int(fy);
    if (fx < 0 || fy < 0 || ix >= raster_.cols - 1 || iy >= raster_.rows - 1) return 0;
    const float ax = float(fx - ix), ay = float(fy - iy);
    const float* r0 = raster_.ptr<float>(iy) + ix;
    const float* r1 = r0 + raster_.cols;
    return (r0[0] * (1 - ax) + r0[1] * ax) * (1 - ay) + (r1[0] * (1 - ax) + r1[1] * ax) * ay;
  }

 private:
  cv::Mat raster_;  // CV_32F, row = y, column = x
  double x0_ = 0, y0_ = 0, inv_texel_ = 1;
};

}  // namespace dv

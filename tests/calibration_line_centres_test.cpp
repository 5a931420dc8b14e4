// Line pixels moved to their line's centre: on a drawn line of known place
// (anti-aliased, blurred, any direction, any sub-pixel offset) the refined
// pixels lie on the centre line within a twentieth of a pixel, where the
// mask's own pixels scatter across the painted width.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/units.h"
#include "geometry/calibration/line_pixels.h"

namespace dv {
namespace {

struct Spread {
  double mean_abs = 0;
  int n = 0;
};

// Distance of the pixels from the line n . p = rho, mean of the absolute
// values, away from the image border (where pixels keep their place).
Spread spread(const std::vector<ImagePx>& px, double nx, double ny, double rho, int size) {
  Spread s;
  for (const auto& p : px)
    if (std::min(p.u, p.v) >= 30 && std::max(p.u, p.v) < size - 30)
      s.mean_abs += std::abs(nx * p.u + ny * p.v - rho), ++s.n;
  if (s.n) s.mean_abs /= s.n;
  return s;
}

TEST(LineCentres, RefinedPixelsLieOnTheDrawnLineAtAnyAngleAndOffset) {
  const int size = 240;
  const double width_px = 3.2;
  for (double deg = 0; deg < 180; deg += 17) {
    for (double offset : {0.0, 0.25, 0.5, 0.8}) {
      const double th = deg * kPi / 180, nx = std::cos(th), ny = std::sin(th);
      const double rho = nx * size / 2 + ny * size / 2 + offset;
      cv::Mat gray(size, size, CV_32F);
      for (int v = 0; v < size; ++v)
        for (int u = 0; u < size; ++u) {
          // 4x4 supersampled coverage of the painted width.
          double cover = 0;
          for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b)
              cover += std::abs(nx * (u + (a - 1.5) / 4) + ny * (v + (b - 1.5) / 4) - rho) <= width_px / 2;
          gray.at<float>(v, u) = float(70 + 150 * cover / 16);
        }
      cv::GaussianBlur(gray, gray, cv::Size(0, 0), 0.7);
      cv::Mat g8, bgr;
      gray.convertTo(g8, CV_8U);
      cv::cvtColor(g8, bgr, cv::COLOR_GRAY2BGR);
      LinePixelOptions o;
      o.half_width_px = halfLineWidthPx(10.0 / width_px, 10.0);
      const std::vector<ImagePx> mask = maskPixels(detectLinePixels(bgr, o), 100000);
      std::vector<ImagePx> refined = mask;
      refineToLineCentres(lineBrightness(bgr), o.half_width_px, refined);
      const Spread before = spread(mask, nx, ny, rho, size), after = spread(refined, nx, ny, rho, size);
      ASSERT_GT(before.n, 100) << deg << " deg";
      EXPECT_LT(after.mean_abs, 0.05) << deg << " deg, offset " << offset << " (mask pixels " << before.mean_abs << ")";
      EXPECT_GT(before.mean_abs, 0.3) << "the mask pixels scatter across the width";
    }
  }
}

}  // namespace
}  // namespace dv

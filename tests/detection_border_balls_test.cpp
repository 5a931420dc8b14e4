// Balls cut by the image border (detection/border_balls.h) on drawn frames:
// a disc of the ball's image radius, its rim anti-aliased, on a plain
// carpet, judged by a plain color test. Half or more of it in view: found,
// its center where it was drawn; a whole ball near the edge: found whole;
// a colored band along the edge: no border ball.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

#include "detection/border_balls.h"
#include "synth/scene.h"

namespace dv {
namespace {

struct RedTest final : BallColorTest {
  bool isBall(const float rgb[3]) const override { return rgb[0] > 128; }
  bool isCarpet(const float rgb[3]) const override { return rgb[1] > rgb[0] && rgb[1] > rgb[2]; }
};

constexpr double kBall = 21.5;

struct Drawn {
  CameraModel cam;
  cv::Mat image;
  double r_px = 0;
};

// A camera 4 m above the field looking down, and its frame with carpet.
Drawn topDown() {
  const SceneCamera c = makeCamera(0, {0, 0, 4000}, {0, 0, 0}, 900, 0, {0, 0}, 640, 480);
  Drawn d{CameraModel(c.calib), cv::Mat(480, 640, CV_8UC3, cv::Scalar(40, 110, 40)), 0};
  d.r_px = ballRadiusPx(d.cam, *d.cam.imageToField({320, 240}, kBall), kBall);
  return d;
}

// Paints `inside(u, v)` (sub-pixel) red, each pixel by its 4 x 4 coverage.
template <class Inside>
void paint(cv::Mat& im, Inside&& inside) {
  for (int y = 0; y < im.rows; ++y)
    for (int x = 0; x < im.cols; ++x) {
      int n = 0;
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) n += inside(x - 0.375 + 0.25 * i, y - 0.375 + 0.25 * j);
      if (n == 0) continue;
      const double a = n / 16.0;
      cv::Vec3b& p = im.at<cv::Vec3b>(y, x);
      p = cv::Vec3b(static_cast<uchar>((1 - a) * p[0] + a * 20), static_cast<uchar>((1 - a) * p[1] + a * 100),
                    static_cast<uchar>((1 - a) * p[2] + a * 250));
    }
}

std::vector<BorderBall> findIn(const Drawn& d) {
  BorderBallFinder finder(d.cam, FieldRect{-4800, 4800, -3300, 3300}, kBall);
  EXPECT_GT(finder.probes(), 100);
  std::vector<BorderBall> out;
  const FrameView view{&d.image, BayerPattern::None};
  finder.find(view, RedTest{}, out);
  return out;
}

TEST(BorderBalls, HalfOrMoreInViewIsFoundWhereItLies) {
  for (double k : {0.0, 0.3, 0.7}) {
    Drawn d = topDown();
    ASSERT_GT(d.r_px, 4);
    // Left edge (u = -0.5) and the bottom edge (v = 479.5), k radii inside.
    const ImagePx left{-0.5 + k * d.r_px, 200}, bottom{400, 479.5 - k * d.r_px};
    for (const ImagePx& c : {left, bottom})
      paint(d.image, [&](double u, double v) { return std::hypot(u - c.u, v - c.v) <= d.r_px; });
    const auto balls = findIn(d);
    ASSERT_EQ(balls.size(), 2u) << k << " radii in";
    for (const ImagePx& c : {left, bottom}) {
      double best = 1e9;
      for (const BorderBall& b : balls) best = std::min(best, std::hypot(b.center.u - c.u, b.center.v - c.v));
      EXPECT_LT(best, 1.0) << k << " radii in";
    }
    for (const BorderBall& b : balls) EXPECT_GE(b.visible, 0.45);
  }
}

TEST(BorderBalls, BandsAreNoBalls) {
  Drawn d = topDown();
  // A red band along the top edge and a ball-deep stripe on the right edge
  // as long as three balls.
  const double r = d.r_px;
  paint(d.image, [&](double u, double v) {
    return (v < 0.6 * r && u > 100 && u < 500) || (u > 639.5 - r && v > 100 && v < 100 + 6 * r);
  });
  const auto found = findIn(d);
  for (const BorderBall& b : found) ADD_FAILURE() << "a ball at " << b.center.u << ", " << b.center.v;
}

// A whole ball too near the edge for the blob score's windows (they reach
// about three radii beyond it) is found whole, once, where it lies.
TEST(BorderBalls, WholeBallsNearTheEdgeAreFoundWhole) {
  for (double k : {1.2, 1.5, 2.0, 3.0, 3.9}) {
    Drawn d = topDown();
    const ImagePx c{-0.5 + k * d.r_px, 300};
    paint(d.image, [&](double u, double v) { return std::hypot(u - c.u, v - c.v) <= d.r_px; });
    const auto balls = findIn(d);
    ASSERT_EQ(balls.size(), 1u) << k << " radii in";
    EXPECT_TRUE(balls[0].whole) << k << " radii in";
    EXPECT_LT(std::hypot(balls[0].center.u - c.u, balls[0].center.v - c.v), 0.5) << k << " radii in";
  }
}

}  // namespace
}  // namespace dv

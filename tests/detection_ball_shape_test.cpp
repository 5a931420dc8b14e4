// The ball's shape in the frame (ball_silhouette.h) on painted images: a
// ball's disc keeps its color within its rim, a line crossing in the ball's
// color runs on beyond it.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "detection/ball_silhouette.h"

namespace dv {
namespace {

// Painted colors: orange is the ball's, green the carpet's.
const cv::Scalar kCarpetBgr(40, 110, 50), kOrangeBgr(30, 110, 230);

class PaintedColors final : public BallColorTest {
 public:
  bool isBall(const float rgb[3]) const override { return rgb[0] > 150 && rgb[2] < 100; }
  bool isCarpet(const float rgb[3]) const override { return rgb[1] > rgb[0] && rgb[1] > rgb[2]; }
};

constexpr double kRadiusPx = 8;
const ImagePx kCenter{100, 100};

TEST(BallShape, ABallsColorStaysWithinItsRim) {
  cv::Mat image(200, 200, CV_8UC3, kCarpetBgr);
  cv::circle(image, {100, 100}, static_cast<int>(kRadiusPx), kOrangeBgr, cv::FILLED, cv::LINE_AA);
  const FrameView frame{&image, BayerPattern::None};
  EXPECT_FALSE(ballColorBeyondRim(frame, PaintedColors(), kCenter, kRadiusPx));
  ImagePx center;
  ASSERT_TRUE(ballSilhouetteCenter(frame, PaintedColors(), {102, 101}, kRadiusPx, center));
  EXPECT_NEAR(center.u, 100, 0.3);
  EXPECT_NEAR(center.v, 100, 0.3);
}

TEST(BallShape, ACrossingInTheBallsColorRunsOnBeyondTheRim) {
  // Two lines 3 px wide crossing where a ball would be: as much ball color
  // near the middle as a ball's disc has, but along the lines.
  cv::Mat image(200, 200, CV_8UC3, kCarpetBgr);
  cv::line(image, {60, 100}, {140, 100}, kOrangeBgr, 3);
  cv::line(image, {100, 60}, {100, 140}, kOrangeBgr, 3);
  const FrameView frame{&image, BayerPattern::None};
  EXPECT_TRUE(ballColorBeyondRim(frame, PaintedColors(), kCenter, kRadiusPx));
  ImagePx center;
  EXPECT_FALSE(ballSilhouetteCenter(frame, PaintedColors(), kCenter, kRadiusPx, center));
}

TEST(BallShape, NothingIsJudgedWhereTheLatticeLeavesTheImage) {
  cv::Mat image(200, 200, CV_8UC3, kCarpetBgr);
  cv::line(image, {0, 4}, {60, 4}, kOrangeBgr, 3);
  const FrameView frame{&image, BayerPattern::None};
  EXPECT_FALSE(ballColorBeyondRim(frame, PaintedColors(), {30, 4}, kRadiusPx));
}

}  // namespace
}  // namespace dv

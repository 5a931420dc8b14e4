// A ball in a marker's color (marker_colored_ball.h) on painted images: a
// yellow disc alone on the carpet stands on carpet all round, a yellow
// center dot on a robot's dark top does not; the ball's own colors and its
// marker class both count as the ball's.
#include <gtest/gtest.h>

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "detection/frame_blob.h"
#include "detection/marker_colored_ball.h"

namespace dv {
namespace {

using namespace color_class;

// Painted colors (RGB), and the frame's classes learned from them.
constexpr float kCarpet[3] = {50, 110, 40}, kYellowDot[3] = {240, 210, 20}, kTop[3] = {25, 25, 25},
                kOrangeBall[3] = {230, 110, 30}, kLine[3] = {230, 230, 230}, kGreenDot[3] = {60, 190, 60},
                kPinkDot[3] = {230, 60, 140}, kBlueDot[3] = {30, 60, 200};

cv::Scalar bgr(const float rgb[3]) { return cv::Scalar(rgb[2], rgb[1], rgb[0]); }
ColorVec feature(const float rgb[3]) { return colorFeature(rgb[0], rgb[1], rgb[2]); }

FrameColors paintedColors() {
  FrameColors f;
  const float* rgb[kNumClasses] = {kYellowDot, kBlueDot, kGreenDot, kPinkDot, kOrangeBall, kCarpet, kLine};
  for (int k = 0; k < kNumClasses; ++k) f.color[k] = feature(rgb[k]), f.spread[k] = 2, f.seen[k] = true;
  return f;
}

// The frame's judge for the test's purpose: orange is the ball's, the
// field's class the carpet.
class OrangeOnly final : public BallColorTest {
 public:
  bool isBall(const float rgb[3]) const override { return colorDistance(feature(rgb), feature(kOrangeBall)) < 8; }
  bool isCarpet(const float rgb[3]) const override { return colorDistance(feature(rgb), feature(kCarpet)) < 8; }
};

constexpr double kBallRadiusMm = 21.5, kRadiusPx = 8;
const ImagePx kCenter{100, 100};

cv::Mat carpet() { return cv::Mat(200, 200, CV_8UC3, bgr(kCarpet)); }

TEST(MarkerColoredBall, AYellowDiscAloneOnTheCarpetStandsOnCarpet) {
  cv::Mat image = carpet();
  cv::circle(image, {100, 100}, static_cast<int>(kRadiusPx), bgr(kYellowDot), cv::FILLED, cv::LINE_AA);
  const FrameView frame{&image, BayerPattern::None};
  const float brightness = kYellowDot[0] + kYellowDot[1] + kYellowDot[2];
  const FrameColors colors = paintedColors();
  EXPECT_EQ(carpetAroundBall(frame, &colors, kCenter, kRadiusPx, kBallRadiusMm, brightness), 1.0);
}

TEST(MarkerColoredBall, ACenterDotOnARobotsTopStandsOnNoCarpet) {
  // A robot's top (85 mm, about 4 ball radii) around a yellow center dot.
  cv::Mat image = carpet();
  cv::circle(image, {100, 100}, static_cast<int>(85 / kBallRadiusMm * kRadiusPx), bgr(kTop), cv::FILLED);
  cv::circle(image, {100, 100}, static_cast<int>(25 / kBallRadiusMm * kRadiusPx), bgr(kYellowDot), cv::FILLED);
  const FrameView frame{&image, BayerPattern::None};
  const float brightness = kYellowDot[0] + kYellowDot[1] + kYellowDot[2];
  const FrameColors colors = paintedColors();
  int may_be_top = 0;
  EXPECT_EQ(carpetAroundBall(frame, &colors, kCenter, kRadiusPx, kBallRadiusMm, brightness, &may_be_top), 0.0);
  EXPECT_GT(may_be_top, 0);
  // Without the frame's classes only the top's darkness tells it.
  EXPECT_EQ(carpetAroundBall(frame, nullptr, kCenter, kRadiusPx, kBallRadiusMm, brightness), 0.0);
}

TEST(MarkerColoredBall, WithoutClassesACarpetOfAnyColorStandsAroundTheBall) {
  // Carpet the frame's classes would call yellow (a cold cast's pale yellow
  // centers lie near it) up to a robot's reach, the field's beyond: by
  // color no carpet, by darkness no robot top.
  cv::Mat image = carpet();
  cv::circle(image, {100, 100}, static_cast<int>(70 / kBallRadiusMm * kRadiusPx), bgr(kYellowDot) * 0.6, cv::FILLED);
  cv::circle(image, {100, 100}, static_cast<int>(kRadiusPx), bgr(kOrangeBall), cv::FILLED, cv::LINE_AA);
  const FrameView frame{&image, BayerPattern::None};
  const float brightness = kOrangeBall[0] + kOrangeBall[1] + kOrangeBall[2];
  const FrameColors colors = paintedColors();
  EXPECT_EQ(carpetAroundBall(frame, &colors, kCenter, kRadiusPx, kBallRadiusMm, brightness), 0.0);
  EXPECT_EQ(carpetAroundBall(frame, nullptr, kCenter, kRadiusPx, kBallRadiusMm, brightness), 1.0);
}

// The ring is the carpet where it looks like the carpet beyond a robot's
// reach (105 mm), whatever the classes say and however dark it is beside
// the ball: a red ball on a dark carpet, a lit carpet clipped to a team's
// color. A robot's dark top is not that carpet.
TEST(MarkerColoredBall, ACarpetLikeTheCarpetBeyondARobotsReachIsCarpet) {
  const float dark[3] = {20, 40, 16};
  cv::Mat image(200, 200, CV_8UC3, bgr(dark));
  cv::circle(image, {100, 100}, static_cast<int>(kRadiusPx), bgr(kOrangeBall), cv::FILLED, cv::LINE_AA);
  const FrameView frame{&image, BayerPattern::None};
  const float brightness = kOrangeBall[0] + kOrangeBall[1] + kOrangeBall[2];
  ASSERT_LT(dark[0] + dark[1] + dark[2], kTopBrightness * brightness);
  const FrameColors colors = paintedColors();
  EXPECT_EQ(carpetAroundBall(frame, &colors, kCenter, kRadiusPx, kBallRadiusMm, brightness), 1.0);
  EXPECT_EQ(carpetAroundBall(frame, nullptr, kCenter, kRadiusPx, kBallRadiusMm, brightness), 1.0);

  cv::Mat blue(200, 200, CV_8UC3, bgr(kBlueDot));
  cv::circle(blue, {100, 100}, static_cast<int>(kRadiusPx), bgr(kYellowDot), cv::FILLED, cv::LINE_AA);
  const FrameView lit{&blue, BayerPattern::None};
  EXPECT_EQ(carpetAroundBall(lit, &colors, kCenter, kRadiusPx, kBallRadiusMm, brightness), 1.0);

  // The same dark carpet around a robot's top: the ring is the top.
  cv::circle(image, {100, 100}, static_cast<int>(85 / kBallRadiusMm * kRadiusPx), bgr(kTop), cv::FILLED);
  cv::circle(image, {100, 100}, static_cast<int>(25 / kBallRadiusMm * kRadiusPx), bgr(kOrangeBall), cv::FILLED);
  EXPECT_EQ(carpetAroundBall(frame, &colors, kCenter, kRadiusPx, kBallRadiusMm, brightness), 0.0);
  EXPECT_EQ(carpetAroundBall(frame, nullptr, kCenter, kRadiusPx, kBallRadiusMm, brightness), 0.0);
}

TEST(MarkerColoredBall, ALineBesideTheBallLeavesMostOfItsRingOnCarpet) {
  cv::Mat image = carpet();
  cv::line(image, {0, 114}, {199, 114}, bgr(kLine), 3);
  cv::circle(image, {100, 100}, static_cast<int>(kRadiusPx), bgr(kYellowDot), cv::FILLED, cv::LINE_AA);
  const FrameView frame{&image, BayerPattern::None};
  const float brightness = kYellowDot[0] + kYellowDot[1] + kYellowDot[2];
  const FrameColors colors = paintedColors();
  int may_be_top = -1;
  const double share = carpetAroundBall(frame, &colors, kCenter, kRadiusPx, kBallRadiusMm, brightness, &may_be_top);
  EXPECT_GT(share, 0.5);
  EXPECT_LT(share, 1.0);
  EXPECT_EQ(may_be_top, 0);  // a line is no robot's top
}

TEST(MarkerColoredBall, TheMarkersClassAndTheBallsOwnColorsAreBoth) {
  const FrameColors colors = paintedColors();
  const OrangeOnly judge;
  const MarkerColoredBallTest yellow(colors, judge, kYellow);
  EXPECT_TRUE(yellow.isBall(kYellowDot));
  EXPECT_TRUE(yellow.isBall(kOrangeBall));
  EXPECT_FALSE(yellow.isBall(kCarpet));
  EXPECT_FALSE(yellow.isBall(kPinkDot));
  // A pale yellow (a line's false color) lies beyond the class's reach.
  const float pale[3] = {205, 205, 110};
  EXPECT_FALSE(yellow.isBall(pale));
}

// The sun patch that clips the ball lights the carpet around it too: a lit
// carpet within the marker's reach, nearer to it than to the field class,
// is no ball where it lies nearer to the ring's carpet than to the marker.
TEST(MarkerColoredBall, CarpetLitLikeTheMarkerIsTheRingsCarpet) {
  const FrameColors colors = paintedColors();
  const OrangeOnly judge;
  float lit[3], lit_more[3];
  for (int k = 0; k < 3; ++k)
    lit[k] = 0.15f * kCarpet[k] + 0.85f * kYellowDot[k], lit_more[k] = 0.2f * kCarpet[k] + 0.8f * kYellowDot[k];
  const ColorVec ring = feature(lit_more);
  const MarkerColoredBallTest yellow(colors, judge, kYellow), yellow_on_lit(colors, judge, kYellow, &ring);
  ASSERT_TRUE(yellow.isBall(lit));
  EXPECT_FALSE(yellow_on_lit.isBall(lit));
  EXPECT_TRUE(yellow_on_lit.isBall(kYellowDot));
}

// An over-exposed ball's unclipped rim is its color mixed with the carpet
// around it. In a sun patch that carpet is lit, its chromaticity off the
// field class's: the mix with it is a rim only where the ring's color is
// given (colorAroundBall).
TEST(MarkerColoredBall, AnOverExposedRimMixesWithTheCarpetAroundIt) {
  const FrameColors colors = paintedColors();
  const OrangeOnly judge;
  const float lit[3] = {140, 250, 200};
  float rim[3];
  for (int k = 0; k < 3; ++k) rim[k] = (kYellowDot[k] + lit[k]) / 2;
  const ColorVec around = feature(lit);
  const MarkerColoredBallTest yellow(colors, judge, kYellow), yellow_on_lit(colors, judge, kYellow, &around);
  EXPECT_FALSE(yellow.isRim(rim));
  EXPECT_TRUE(yellow_on_lit.isRim(rim));
  // A mix with the field class's carpet is a rim either way; a pink dot's
  // mix with the lit carpet is none.
  float field_rim[3], pink_rim[3];
  for (int k = 0; k < 3; ++k)
    field_rim[k] = (kYellowDot[k] + kCarpet[k]) / 2, pink_rim[k] = (kPinkDot[k] + lit[k]) / 2;
  EXPECT_TRUE(yellow.isRim(field_rim));
  EXPECT_TRUE(yellow_on_lit.isRim(field_rim));
  EXPECT_FALSE(yellow_on_lit.isRim(pink_rim));
}

// More light clips the ball along its own path, orange to a pale yellow
// whose blue is the ball's, not the yellow centers': a rim of that mixed
// with the lit carpet is a rim too. A pink dot clipped alike is none.
// Nearest to no marker (a pale yellow nearer to the lines' white), only the
// ball's own colors count, not a class's.
TEST(MarkerColoredBall, AnOverExposedRimMayMixTheBallsOwnClippedColor) {
  const FrameColors colors = paintedColors();
  const OrangeOnly judge;
  const float lit[3] = {140, 250, 200};
  const ColorVec around = feature(lit);
  const MarkerColoredBallTest yellow(colors, judge, kYellow, &around), own(colors, judge, -1, &around);
  float ball_rim[3], pink_rim[3], yellow_rim[3];
  for (int k = 0; k < 3; ++k) {
    ball_rim[k] = (std::min(255.f, 2.5f * kOrangeBall[k]) + lit[k]) / 2;
    pink_rim[k] = (std::min(255.f, 2.5f * kPinkDot[k]) + lit[k]) / 2;
    yellow_rim[k] = (kYellowDot[k] + kCarpet[k]) / 2;
  }
  EXPECT_TRUE(yellow.isRim(ball_rim));
  EXPECT_FALSE(yellow.isRim(pink_rim));
  EXPECT_TRUE(own.isRim(ball_rim));
  EXPECT_FALSE(own.isRim(pink_rim));
  ASSERT_TRUE(yellow.isRim(yellow_rim));
  EXPECT_FALSE(own.isRim(yellow_rim));
  EXPECT_FALSE(own.isBall(kYellowDot));
  EXPECT_TRUE(own.isBall(kOrangeBall));
}

}  // namespace
}  // namespace dv

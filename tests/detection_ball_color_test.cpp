// The ball's color judge (ball_color.h) on the colors one frame showed: a
// tungsten cast, desaturated, with vignetting, where the lines' white and
// the lit yellow centers clip red and their darker parts do not (the
// rendered sweep's tungsten_desaturated_vignetting_blur, colors as the
// detector read them).
#include "detection/ball_color.h"

#include <gtest/gtest.h>

#include <array>

namespace dv {
namespace {

using namespace color_class;

ColorVec feature(float r, float g, float b) { return colorFeature(r, g, b); }

FrameColors tungstenFrame() {
  FrameColors f;
  f.white.valid = true;
  f.white.rgb[0] = 174, f.white.rgb[1] = 181, f.white.rgb[2] = 132;
  f.color[kYellow] = feature(236, 167, 82);
  f.color[kBlue] = feature(92, 112, 150);
  f.color[kGreen] = feature(120, 170, 80);
  f.color[kPink] = feature(225, 120, 118);
  f.color[kField] = feature(70, 105, 45);
  f.color[kWhite] = feature(174, 181, 132);
  f.color[kOrange] = feature(255, 110, 10);  // the reference: far from this frame's ball
  for (int k = 0; k < kNumClasses; ++k) f.seen[k] = true;
  f.spread[kYellow] = 7.6f;  // lit (clipped) and vignetted centers
  f.spread[kField] = 3.f;
  // The reddest yellow center, a vignetted one that did not clip.
  const float reddest[3] = {205, 143, 70};
  f.yellow_hue_min = colorHue(reddest, f.white.rgb);
  return f;
}

constexpr float kMinBrightness = 150;

TEST(BallColor, BallRedderThanEveryYellowCenterIsTheBall) {
  const FrameColors f = tungstenFrame();
  const BallColorJudge judge(f, kMinBrightness);
  const float ball[3] = {200, 111, 62};
  // Within the yellow class's reach around its mean ...
  EXPECT_LT(ClippedColor(ball).distance(f.color[kYellow]), kClassSpreads * f.spread[kYellow]);
  // ... but redder than every yellow center the frame shows.
  EXPECT_GT(judge.explainedByNone(ball), 1.f);
  EXPECT_GT(judge.confidence(ball, false), 0.3);
  EXPECT_TRUE(judge.isBall(ball));
}

TEST(BallColor, YellowCenterAsRedAsTheBallExplainsIt) {
  FrameColors f = tungstenFrame();
  const float ball[3] = {200, 111, 62};
  f.yellow_hue_min = colorHue(ball, f.white.rgb);
  const BallColorJudge judge(f, kMinBrightness);
  EXPECT_LE(judge.explainedByNone(ball), 1.f);
  EXPECT_EQ(judge.confidence(ball, false), 0);
}

TEST(BallColor, LineCrossingUnderTheCastIsNoBall) {
  const FrameColors f = tungstenFrame();
  const BallColorJudge judge(f, kMinBrightness);
  // Vignetted line crossings, redder than the clipped lines' white: their
  // raw colors are as saturated as a ball's share of the yellow's, under
  // the lines' white they are not.
  for (const auto& c : {std::array<float, 3>{203, 176, 126}, {160, 128, 92}, {188, 152, 105}}) {
    EXPECT_EQ(judge.explainedByNone(c.data()), 0) << c[0] << " " << c[1] << " " << c[2];
    EXPECT_EQ(judge.confidence(c.data(), false), 0) << c[0] << " " << c[1] << " " << c[2];
  }
}

TEST(BallColor, CarpetAndTeamColorsAreNoBall) {
  const FrameColors f = tungstenFrame();
  const BallColorJudge judge(f, kMinBrightness);
  const float carpet[3] = {72, 104, 46}, yellow[3] = {236, 167, 82}, pink[3] = {225, 120, 118};
  EXPECT_TRUE(judge.isCarpet(carpet));
  EXPECT_FALSE(judge.isBall(carpet));
  EXPECT_FALSE(judge.isBall(yellow));
  EXPECT_FALSE(judge.isBall(pink));
  // Orange itself, as the reference says, is the ball's.
  const float orange[3] = {250, 110, 15};
  EXPECT_TRUE(judge.isBall(orange));
}

// A fast ball kicked under tungsten, in H.264 at 3 Mbit/s (1224 x 1024):
// the stream kept its streak's brightness and about half its chroma, and
// faded, (231, 108, 62) lies nearer to pink than to orange. A streak's
// color is judged with its chroma faded toward the frame's white by up to
// half (kStreakMinChroma), every class's alike (colors as the detector
// read them in frame 0 of the motion preset under that cast).
FrameColors tungstenStreamFrame() {
  FrameColors f;
  f.white.valid = true;
  f.white.rgb[0] = 229, f.white.rgb[1] = 218, f.white.rgb[2] = 148;
  f.color[kYellow] = {{146, 120, 25}};
  f.color[kBlue] = {{72, 85, 119}};
  f.color[kGreen] = {{83, 151, 52}};
  f.color[kPink] = {{166, 53, 71}};
  f.color[kOrange] = {{187, 88, 15}};
  f.color[kField] = {{56, 153, 70}};
  f.color[kWhite] = {{113, 107, 73}};
  for (int k = 0; k < kNumClasses; ++k) f.seen[k] = true;
  return f;
}

TEST(BallColor, AStreakWhoseChromaFadedIsStillTheBalls) {
  FrameColors f = tungstenStreamFrame();
  const float faded[3] = {231, 108, 62};
  EXPECT_GT(BallColorJudge(f, kMinBrightness).confidence(faded, true), 0.3);
  // Without the lines' white there is nothing to fade toward: nearer to
  // pink than to anything else, and too weak a ball for the detector's
  // least confidence (DetectorOptions::min_ball_confidence).
  f.white.valid = false;
  int nearest = -1;
  EXPECT_LT(BallColorJudge(f, kMinBrightness).confidence(faded, true, &nearest), 0.3);
  EXPECT_EQ(nearest, kPink);
}

TEST(BallColor, FadedStreaksOfPinkAndOfTheLinesAreNoBall) {
  const FrameColors f = tungstenStreamFrame();
  const BallColorJudge judge(f, kMinBrightness);
  // A pink dot's blur, at full chroma and faded by half toward the white.
  const ColorVec pink = f.color[kPink], half = colorMix(pink, 0.5f, f.color[kWhite], 0.5f, pink, 0.f);
  for (const ColorVec& c : {pink, half}) EXPECT_EQ(judge.confidence(c.c, true), 0) << c.c[0] << " " << c.c[1];
  // The lines mixed with the carpet.
  const float line_mix[3] = {150, 175, 90};
  EXPECT_EQ(judge.confidence(line_mix, true), 0);
}

}  // namespace
}  // namespace dv

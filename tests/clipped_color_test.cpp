// A clipped channel only bounds the true color from below: the overexposed
// ball must read as orange again, while clipped pattern colors stay theirs.
#include <gtest/gtest.h>

#include "detection/clipped_color.h"

namespace dv {
namespace {

ColorVec feature(float r, float g, float b) { return colorFeature(r, g, b); }

// The references of detector.h, seen at 1.6x exposure: red clips first.
TEST(ClippedColor, OverexposedOrangeIsNearerOrangeThanYellow) {
  const ColorVec orange = feature(255, 120, 20), yellow = feature(255, 255, 64);
  const float ball[3] = {246, 186, 41};  // the sweep's clipped ball at 1224 x 1024
  const ClippedColor c(ball);
  ASSERT_TRUE(c.clipped());
  // As seen, the ball is about as near yellow as orange.
  const ColorVec seen = feature(ball[0], ball[1], ball[2]);
  EXPECT_LT(colorDistance(seen, yellow) - colorDistance(seen, orange), 6.f);
  // With red free to have been higher, it is orange.
  EXPECT_LT(c.distance(orange), 8.f);
  EXPECT_GT(c.distance(yellow), 3 * c.distance(orange));
}

TEST(ClippedColor, TwoClippedChannelsSayTooLittle) {
  // A yellow center in a sun patch: red and green clipped. Free to grow,
  // they would reach orange (the ghost ball of the uneven-light preset).
  const float yellow[3] = {255, 255, 71}, pink[3] = {255, 144, 255};
  EXPECT_TRUE(ClippedColor(yellow).saturated());
  EXPECT_TRUE(ClippedColor(pink).saturated());
  // One clipped channel: a clipped pink stays far from orange.
  const float pink_r[3] = {250, 110, 200};
  const ClippedColor p(pink_r);
  ASSERT_FALSE(p.saturated());
  EXPECT_GT(p.distance(feature(255, 120, 20)), 40.f);
}

// A yellow top in the bright corner of a green-cast, desaturated frame: red
// and green clip, blue does not. As seen it is nearer the lines' white than
// the frame's yellow (and its robot was dropped as a line); red and green
// grown together it is the yellow. A clipped white stays white.
TEST(ClippedColor, TwoClippedChannelsGrowTogether) {
  const ColorVec yellow = feature(200, 215, 60), white = feature(230, 255, 225);
  const float center[3] = {255, 255, 195};
  const ClippedColor c(center);
  ASSERT_TRUE(c.saturated());
  const ColorVec seen = feature(center[0], center[1], center[2]);
  EXPECT_LT(colorDistance(seen, white), colorDistance(seen, yellow));
  EXPECT_LT(c.distance(yellow), c.distance(white));
  const float line[3] = {255, 255, 255};
  EXPECT_FLOAT_EQ(ClippedColor(line).distance(yellow), colorDistance(feature(255, 255, 255), yellow));
}

// A sky-blue center in a sun patch under cold LED light: green and blue
// clip, red does not. As seen it is nearer the lines' white than the
// team's blue (its robot was dropped as a line crossing); with its clipped
// channels in the blue's proportions it is the blue. A line that clips
// green and blue shows more red, and stays white.
TEST(ClippedColor, TwoClippedChannelsMayTakeTheTargetsProportions) {
  const ColorVec blue = feature(63, 175, 255), white = feature(105, 150, 255);
  const float center[3] = {138, 255, 255};
  const ClippedColor c(center);
  ASSERT_TRUE(c.saturated());
  const ColorVec seen = feature(center[0], center[1], center[2]);
  EXPECT_LT(colorDistance(seen, white), colorDistance(seen, blue));
  EXPECT_LT(c.distance(blue), 5.f) << c.distance(white);
  EXPECT_GT(c.distance(white), 5 * c.distance(blue));
  const float line[3] = {182, 255, 255};
  const ClippedColor l(line);
  EXPECT_LT(l.distance(white), l.distance(blue));
}

TEST(ClippedColor, UnclippedIsThePlainDistanceAndWhiteSaysNothing) {
  const float dim[3] = {120, 60, 10};
  const ClippedColor d(dim);
  EXPECT_FALSE(d.clipped());
  EXPECT_FLOAT_EQ(d.distance(feature(40, 110, 50)),
                  colorDistance(feature(120, 60, 10), feature(40, 110, 50)));
  const float white[3] = {255, 255, 255};
  EXPECT_TRUE(ClippedColor(white).saturated());
}

}  // namespace
}  // namespace dv

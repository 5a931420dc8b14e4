// The color warnings (detection/color_health.h): each starts after its
// evidence held for the configured frames, is said once, ends the same way,
// and is counted for the summary.
#include <gtest/gtest.h>

#include "detection/color_health.h"

namespace dv {
namespace {

DetectionHealth frame(int yellow, int blue, int balls) {
  DetectionHealth h;
  h.yellow = yellow, h.blue = blue, h.balls = balls;
  h.center_blobs = yellow + blue;
  h.side_blobs = 4 * (yellow + blue);
  h.teams_separated = yellow > 0 && blue > 0;
  h.sides_separated = true;
  return h;
}

constexpr unsigned bit(ColorIssue i) { return 1u << static_cast<int>(i); }

// Feeds `n` copies of h; returns the OR of the changes.
unsigned feed(ColorHealthWatch& w, const DetectionHealth& h, int n) {
  unsigned changed = 0;
  for (int i = 0; i < n; ++i) changed |= w.update(h);
  return changed;
}

TEST(ColorHealth, AMissingTeamIsSaidOnceAfterItsFramesAndItsEndToo) {
  ColorHealthOptions o;
  o.frames_to_change = 5;
  ColorHealthWatch w(o);
  EXPECT_EQ(feed(w, frame(8, 8, 1), 20), 0u);
  // One odd frame says nothing.
  EXPECT_EQ(feed(w, frame(0, 8, 1), 1), 0u);
  EXPECT_EQ(feed(w, frame(8, 8, 1), 3), 0u);
  EXPECT_EQ(feed(w, frame(0, 8, 1), 4), 0u);
  EXPECT_EQ(w.update(frame(0, 8, 1)), bit(ColorIssue::YellowMissing));
  EXPECT_TRUE(w.active(ColorIssue::YellowMissing));
  const std::string text = w.describe(ColorIssue::YellowMissing);
  EXPECT_NE(text.find("no yellow robot"), std::string::npos) << text;
  EXPECT_NE(text.find("8 blue robots"), std::string::npos) << text;
  EXPECT_EQ(feed(w, frame(0, 8, 1), 50), 0u);  // said once
  EXPECT_EQ(feed(w, frame(8, 8, 1), 5), bit(ColorIssue::YellowMissing));
  EXPECT_FALSE(w.active(ColorIssue::YellowMissing));
  EXPECT_EQ(w.evidenceFrames(ColorIssue::YellowMissing), 1 + 4 + 1 + 50);
  EXPECT_NE(w.summary().find("yellow team missing in 56 of"), std::string::npos) << w.summary();
}

TEST(ColorHealth, BlueTeamBallAndSideColorsEachHaveTheirWarning) {
  ColorHealthOptions o;
  o.frames_to_change = 3;
  o.ball_frames_to_change = 6;
  ColorHealthWatch w(o);
  EXPECT_EQ(feed(w, frame(6, 0, 1), 3), bit(ColorIssue::BlueMissing));
  ColorHealthWatch balls(o);
  EXPECT_EQ(feed(balls, frame(6, 6, 0), 5), 0u);
  EXPECT_EQ(balls.update(frame(6, 6, 0)), bit(ColorIssue::BallMissing));
  EXPECT_NE(balls.describe(ColorIssue::BallMissing).find("no ball for 6 frames"), std::string::npos);
  // No robots: a missing ball is no evidence (an empty field).
  ColorHealthWatch empty(o);
  EXPECT_EQ(feed(empty, frame(0, 0, 0), 50), 0u);
  ColorHealthWatch sides(o);
  DetectionHealth one = frame(6, 6, 1);
  one.sides_separated = false;
  EXPECT_EQ(feed(sides, one, 3), bit(ColorIssue::SidesInseparable));
  EXPECT_NE(sides.describe(ColorIssue::SidesInseparable).find("one cluster"), std::string::npos);
}

TEST(ColorHealth, TheCastIsSaidAtTheStartAndWhenItMoves) {
  ColorHealthWatch w;
  DetectionHealth h = frame(8, 8, 1);
  h.lines.valid = true;
  h.lines.rgb[0] = 160, h.lines.rgb[1] = 220, h.lines.rgb[2] = 250;
  w.update(h);
  ASSERT_TRUE(w.castChanged());
  EXPECT_NE(w.describeCast().find("R x1.38"), std::string::npos) << w.describeCast();
  w.update(h);
  EXPECT_FALSE(w.castChanged());
  h.lines.rgb[2] = 200;  // B gain 0.88 -> 1.10
  w.update(h);
  EXPECT_TRUE(w.castChanged());
}

}  // namespace
}  // namespace dv

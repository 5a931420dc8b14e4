#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "geometry/robot_pattern.h"

namespace dv {
namespace {

TEST(RobotPattern, SixteenDistinctPatternsRoundTrip) {
  std::set<int> codes;
  for (int id = 0; id < 16; ++id) {
    auto c = patternColors(id);
    EXPECT_EQ(patternId(c), id);
    codes.insert(int(c[0]) * 8 + int(c[1]) * 4 + int(c[2]) * 2 + int(c[3]));
  }
  EXPECT_EQ(codes.size(), 16u);
}

TEST(RobotPattern, KnownIdsMatchTheLeagueSheet) {
  using M = MarkerColor;
  // id 0: FL P, FR P, BL G, BR P; id 13: FL G, FR P, BL P, BR P.
  EXPECT_EQ(patternColors(0), (std::array<M, 4>{M::Pink, M::Green, M::Pink, M::Pink}));
  EXPECT_EQ(patternColors(13), (std::array<M, 4>{M::Green, M::Pink, M::Pink, M::Pink}));
}

TEST(RobotPattern, SideBlobsTouchTheTopOutline) {
  for (auto b : RobotPatternGeometry::kSideBlobs) {
    EXPECT_NEAR(std::hypot(b.x, b.y), 65.0, 1e-9);
  }
  EXPECT_NEAR(RobotPatternGeometry::kSideBlobs[kFrontLeft].x + 20, 55.0, 1e-9);
}

}  // namespace
}  // namespace dv

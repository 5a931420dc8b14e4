// Ids of robots seen with side blobs missing (detection/partial_ids.h):
// the ids fully seen teammates hold are ruled out.
#include <gtest/gtest.h>

#include <vector>

#include "detection/partial_ids.h"

namespace dv {
namespace {

Hypothesis seen(Team team, int id, uint8_t sides = 0xF) {
  Hypothesis h;
  h.team = team;
  h.id = id;
  h.colors = patternColors(id);
  h.seen_sides = sides;
  return h;
}

// The id whose colors are id's with side s (0..3) of the other color.
int flipped(int id, int s) {
  auto c = patternColors(id);
  c[s] = c[s] == MarkerColor::Green ? MarkerColor::Pink : MarkerColor::Green;
  return patternId(c);
}

TEST(PartialIds, ATeammateHoldingTheOtherIdTellsIt) {
  for (int id = 0; id < 16; ++id)
    for (int s = 0; s < 4; ++s) {
      const uint8_t sides = static_cast<uint8_t>(0xF & ~(1u << s));
      std::vector<Hypothesis> robots = {seen(Team::Blue, id, sides), seen(Team::Blue, flipped(id, s))};
      resolvePartialIds(robots);
      EXPECT_EQ(robots[0].id, id) << "id " << id << ", side " << s << " missing";
      EXPECT_TRUE(robots[0].id_known);
      EXPECT_TRUE(robots[1].id_known);
    }
}

// Two ids left: the guess is the color the robot's colors hold at the
// missing side (the nearer of its green and pink where the frame showed
// something there, identifyRobot; green where it showed nothing).
TEST(PartialIds, TwoFreeIdsLeaveTheGuessedColor) {
  for (MarkerColor guess : {MarkerColor::Green, MarkerColor::Pink}) {
    // Side 0 of id 9 is pink (all four are).
    std::vector<Hypothesis> robots = {seen(Team::Yellow, 9, 0xE), seen(Team::Blue, flipped(9, 0))};
    robots[0].colors[0] = guess;
    resolvePartialIds(robots);
    EXPECT_FALSE(robots[0].id_known) << "the other team's ids rule nothing out";
    EXPECT_EQ(robots[0].colors[0], guess);
    EXPECT_EQ(robots[0].id, guess == MarkerColor::Pink ? 9 : flipped(9, 0));
  }
}

TEST(PartialIds, AtTheBorderThreeTakenOfFourLeaveOne) {
  // Sides 2 and 3 missing: four ids fit; three are held by teammates.
  const int id = 5;
  const int others[3] = {flipped(id, 2), flipped(id, 3), flipped(flipped(id, 2), 3)};
  std::vector<Hypothesis> robots = {seen(Team::Yellow, id, 0x3)};
  for (int o : others) robots.push_back(seen(Team::Yellow, o));
  resolvePartialIds(robots);
  EXPECT_EQ(robots[0].id, id);
  EXPECT_TRUE(robots[0].id_known);
  robots.pop_back();  // two left: a guess
  robots[0] = seen(Team::Yellow, id, 0x3);
  resolvePartialIds(robots);
  EXPECT_FALSE(robots[0].id_known);
}

}  // namespace
}  // namespace dv

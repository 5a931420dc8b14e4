#pragma once
// A robot as the detector's stages hand it on: the blobs of its pattern,
// the fitted pose, its identity and how sure that identity is. Blob
// indices refer to the detector's frame blobs (detector_impl.h).
#include <array>
#include <cstdint>

#include "detection/pattern_fit.h"
#include "geometry/robot_pattern.h"

namespace dv {

struct Hypothesis {
  int blob[kPatternSlots];
  int slot[kPatternSlots];
  int n = 0;
  PatternPose pose;  // fitted at the search height, then at the team height
  double rank = 0;
  double confidence = 0;
  Team team = Team::Yellow;
  int id = 0;
  int track = -1;
  std::array<MarkerColor, 4> colors{};  // side colors, valid where seen
  uint8_t seen_sides = 0;               // bit s-1 set: slot s was seen
  // The id was seen whole, follows from the ids others hold, or comes from
  // a track that once saw the robot whole.
  bool id_known = false;
  bool fullPattern() const { return seen_sides == 0xF; }
};

}  // namespace dv

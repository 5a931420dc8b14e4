#pragma once
// The league's standard robot top: a team-colored center blob and four
// green/pink side blobs whose colors encode the id (16 patterns). Robot
// frame: x forward (flat front), y left; millimetres.
#include <array>

#include "core/units.h"

namespace dv {

enum class Team { Yellow = 0, Blue = 1 };
enum class MarkerColor { Green = 0, Pink = 1 };

// Side blob order: increasing angle from the front: FL, BL, BR, FR.
enum SideBlob { kFrontLeft = 0, kBackLeft = 1, kBackRight = 2, kFrontRight = 3 };

struct RobotPatternGeometry {
  static constexpr double kCenterBlobRadius = 25;
  static constexpr double kSideBlobRadius = 20;
  static constexpr double kSideBlobDistance = 65;  // center to side blob center
  static constexpr double kTopRadius = 85;         // pattern area radius
  static constexpr double kFrontCut = 55;          // flat front, from center
  static constexpr double kMaxRadius = 90;         // rule cylinder
  static constexpr double kMaxHeight = 150;
  // Side blob centers in the robot frame, in SideBlob order.
  static constexpr std::array<FieldMm, 4> kSideBlobs = {
      FieldMm{35.0, 54.772255750516614}, FieldMm{-54.772255750516614, 35.0},
      FieldMm{-54.772255750516614, -35.0}, FieldMm{35.0, -54.772255750516614}};
};

// Side blob colors of pattern `id` (0..15) in SideBlob order (FL, BL, BR, FR).
inline std::array<MarkerColor, 4> patternColors(int id) {
  // FL, FR, BL, BR per id as in the league's pattern sheet; G = 1 here.
  static constexpr unsigned char kTable[16][4] = {
      {0, 0, 1, 0}, {1, 0, 1, 0}, {1, 1, 1, 0}, {0, 1, 1, 0}, {0, 0, 0, 1}, {1, 0, 0, 1},
      {1, 1, 0, 1}, {0, 1, 0, 1}, {1, 1, 1, 1}, {0, 0, 0, 0}, {0, 0, 1, 1}, {1, 1, 0, 0},
      {1, 0, 1, 1}, {1, 0, 0, 0}, {0, 1, 1, 1}, {0, 1, 0, 0}};
  const auto& r = kTable[id & 15];
  auto c = [](unsigned char g) { return g ? MarkerColor::Green : MarkerColor::Pink; };
  return {c(r[0]), c(r[2]), c(r[3]), c(r[1])};
}

// Pattern id of side colors in SideBlob order, the inverse of patternColors.
inline int patternId(const std::array<MarkerColor, 4>& colors) {
  for (int id = 0; id < 16; ++id)
    if (patternColors(id) == colors) return id;
  return -1;  // unreachable: the 16 patterns cover all combinations
}

}  // namespace dv

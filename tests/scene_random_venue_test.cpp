// Venues drawn by scripts/random_venues.py (one frame each at 1224 x 1024,
// 8 + 8 robots, shipped defaults) that showed a rule missing: each scene as
// the script wrote it, held to the bar its rule gave.
#include <gtest/gtest.h>

#include <string>

#include "scene_scoring.h"
#include "synth/scene.h"

namespace dv {
namespace {

using namespace dv::test;

// Venue `seed` as the script writes it: its camera, 8 + 8 robots placed by
// the seed, the ball, then its own materials and lighting (YAML).
SceneScore venueScore(int seed, const std::string& ball, const std::string& materials_and_lighting) {
  const std::string n = std::to_string(seed);
  const std::string yaml = "name: venue_" + n + "\nseed: " + n + R"(
field: division_b
cameras:
  - {id: 0, position: [-2250, 0, 5000], look_at: [-2250, 0, 0], up: [-1, 0, 0], focal_length: 1750,
     distortion: 0.03, principal_offset: [6.5, -4.0], size: [2448, 2048]}
noise_sigma: 1.5
shot_noise: 0.05
lens_blur_px: 0.6
antialias: 2
frames: 1
bayer: true
)" + "ball: {position: " + ball + "}\nrandom_robots: {yellow: 8, blue: 8, camera: 0, margin_px: 60, seed: " + n +
                           "}\n" + materials_and_lighting;
  SceneSpec s = sceneFromYaml(yaml, "venue_" + n);
  halveResolution(s);
  SceneScore score_;
  score(s, 1, true, score_);
  return score_;
}

// Moderate venue #376: a sun patch (1.9) under a cold cast at saturation
// 0.82 lights one green dot of an all-green robot toward white, (222, 250,
// 220). Its three other dots peaked; the read of the fourth split from them
// as the redder, so pink: id 14 for 8. A dot read where no blob was must
// lie on its label's side of the lines' white (robot_identity.cpp).
TEST(SceneRandomVenue, AGreenDotLitTowardWhiteStaysGreen) {
  const SceneScore s = venueScore(376, "[-3714, -242]", R"(materials:
  pink: [255, 140, 190]
  green: [111, 197, 79]
  yellow: [243, 217, 56]
  blue: [47, 90, 173]
  ball: [244, 83, 20]
lighting:
  white_balance: [0.99, 1.09, 1.34]
  saturation: 0.82
  gamma: 0.76
  exposure: 0.98
  uneven_ratio: 1.51
  uneven_direction: -2.00
  sun_patches:
    - {center: [-3714, -242], radii: [600, 500], angle: 0.3, gain: 1.90, softness: 0.25}
)");
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Extreme venue #157: a brighter sun patch (2.05) under a magenta cast at
// saturation 0.41 clips a pink dot to (242, 247, 241), which has no hue
// left: by its side of the lines' white it read green (id 8 for 2). Such
// a dot keeps the label the split gives it, the redder of the robot's dots.
TEST(SceneRandomVenue, ADotClippedWhiteKeepsItsSplit) {
  const SceneScore s = venueScore(157, "[-2607, -575]", R"(materials:
  pink: [249, 118, 183]
  green: [137, 206, 60]
  yellow: [241, 232, 71]
  blue: [42, 80, 164]
  ball: [242, 76, 20]
lighting:
  white_balance: [1.05, 0.89, 1.27]
  saturation: 0.41
  gamma: 0.95
  exposure: 0.94
  uneven_ratio: 2.63
  uneven_direction: -2.57
  sun_patches:
    - {center: [-2607, -575], radii: [600, 500], angle: 0.3, gain: 2.05, softness: 0.25}
)");
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Extreme venue #56: a sun patch of 2.24 over the ball under a cold cast
// lights the carpet around it into weak peaks where a pattern's dots would
// lie: a robot of the clipped ball and the carpet, and no ball. A weak peak
// colored as the carpet just beyond the robot's rim, and no brighter than
// a marker over it, is no marker (hypothesis_search.cpp).
TEST(SceneRandomVenue, ALitBallAmongCarpetPeaksIsNoRobot) {
  const SceneScore s = venueScore(56, "[-3216, 1243]", R"(materials:
  pink: [249, 117, 183]
  green: [105, 195, 84]
  yellow: [241, 235, 75]
  blue: [45, 86, 169]
  ball: [240, 70, 20]
lighting:
  white_balance: [0.73, 1.02, 1.66]
  saturation: 0.83
  gamma: 1.12
  exposure: 1.26
  uneven_ratio: 2.98
  uneven_direction: -0.50
  sun_patches:
    - {center: [-3216, 1243], radii: [600, 500], angle: 0.3, gain: 2.24, softness: 0.25}
)");
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.ballRecall(), 1.0);
}

}  // namespace
}  // namespace dv

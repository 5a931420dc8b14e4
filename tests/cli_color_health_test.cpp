// `dotvision run` says when a color class goes missing: a field whose
// yellow robots are out of view (or lost to the camera's colors) is
// reported, in the summary and, once enough frames agree, as a warning;
// the white lines' cast is printed at the start.
#include <gtest/gtest.h>

#include <fstream>

#include "cli_process.h"
#include "temp_dir.h"

namespace dv {
namespace {

// Blue robots only, under a cold cast; `frames` frames of a still scene.
std::string blueOnlyScene(int frames) {
  return std::string(R"(name: blue_only
seed: 3
field: division_b
cameras:
  - {id: 0, position: [-2250, 0, 5000], look_at: [-2250, 0, 0], up: [-1, 0, 0], focal_length: 875, distortion: 0.03, size: [1224, 1024]}
random_robots: {yellow: 0, blue: 6, camera: 0, margin_px: 40}
lighting:
  white_balance: [0.75, 1.0, 1.3]
noise_sigma: 1.0
frames: )") + std::to_string(frames) + "\n";
}

TEST(CliColorHealth, AMissingTeamIsCountedInTheSummaryAndTheCastPrinted) {
  TempDir dir("dv_color_health");
  const std::string scene = (dir.path() / "scene.yaml").string();
  std::ofstream(scene) << blueOnlyScene(1);
  std::string out;
  ASSERT_EQ(runCli("run --scene " + scene + " --no-publish", out), 0) << out;
  EXPECT_NE(out.find("colors, camera 0: yellow team missing in 1 of 1 frames"), std::string::npos) << out;
  EXPECT_NE(out.find("the white lines read"), std::string::npos) << out;
}

TEST(CliColorHealth, AMissingTeamIsWarnedOnceAfterHalfASecond) {
  TempDir dir("dv_color_health_seq");
  const std::string scene = (dir.path() / "scene.yaml").string();
  std::ofstream(scene) << blueOnlyScene(40);
  std::string out;
  ASSERT_EQ(runCli("run --scene " + scene + " --no-publish", out), 0) << out;
  const std::string warning = "warning: camera 0: yellow team missing: no yellow robot for 30 frames";
  const size_t at = out.find(warning);
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_EQ(out.find(warning, at + 1), std::string::npos) << "said twice:\n" << out;
}

}  // namespace
}  // namespace dv

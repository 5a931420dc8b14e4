// Robot heights: positions are projected along the camera ray to the
// team's height, so a wrong height shifts robots away from the camera's
// axis and two overlapping cameras disagree. With the true height given
// (`run --robot-height`), the error is back to the blob accuracy and the
// cameras agree.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "dotvision/ssl_wrapper.pb.h"
#include "eval/metrics.h"
#include "geometry/proto_json.h"
#include "temp_dir.h"

namespace dv {
namespace {

// Two cameras 5 m up over a Division B field, overlapping around the
// halfway line, with 145 mm robots spread over both views and the overlap.
const char* kScene = R"(name: tall_robots
seed: 5
field: division_b
cameras:
  - {id: 0, position: [-1500, 0, 5000], look_at: [-1500, 0, 0], up: [-1, 0, 0], focal_length: 1750, distortion: 0.03, size: [2448, 2048]}
  - {id: 1, position: [1500, 50, 4900], look_at: [1500, 50, 0], up: [-1, 0, 0], focal_length: 1740, distortion: 0.025, size: [2448, 2048]}
robots:
  - {team: yellow, id: 0, position: [-300, 800], orientation: 0.3, height: 145}
  - {team: yellow, id: 1, position: [200, -900], orientation: 2.0, height: 145}
  - {team: yellow, id: 2, position: [-2600, 1400], orientation: -1.0, height: 145}
  - {team: yellow, id: 3, position: [2500, -1300], orientation: 1.5, height: 145}
  - {team: blue, id: 0, position: [250, 300], orientation: -2.0, height: 145}
  - {team: blue, id: 1, position: [-150, -1400], orientation: 1.2, height: 145}
  - {team: blue, id: 2, position: [-2800, -1200], orientation: 0.7, height: 145}
  - {team: blue, id: 3, position: [2700, 1500], orientation: -0.4, height: 145}
noise_sigma: 1.0
frames: 1
)";

struct HeightRun {
  double median_mm = -1;
  std::map<std::pair<int, int>, std::vector<std::pair<double, double>>> by_robot;  // (team, id) -> per camera
  std::vector<double> heights;
};

HeightRun runScene(const TempDir& dir, const std::string& extra) {
  const std::string scene = dir.file("tall.yaml"), jsonl = dir.file("det" + std::to_string(extra.size()) + ".jsonl");
  std::ofstream(scene) << kScene;
  const std::string out = dir.file("out.txt");
  const std::string cmd = std::string("'") + DV_CLI_PATH + "' run --scene " + scene + " --no-publish --jsonl " +
                          jsonl + " " + extra + " >" + out + " 2>&1";
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd;
  std::ifstream o(out);
  std::stringstream text;
  text << o.rdbuf();
  HeightRun r;
  const std::string s = text.str();
  const size_t at = s.find("position error median ");
  EXPECT_NE(at, std::string::npos) << s;
  if (at != std::string::npos) r.median_mm = std::stod(s.substr(at + 22));
  std::ifstream in(jsonl);
  std::string line;
  while (std::getline(in, line)) {
    ssl::SSL_WrapperPacket p;
    parseCanonicalJson(line, p, jsonl);
    for (int team = 0; team < 2; ++team) {
      const auto& robots = team == 0 ? p.detection().robots_yellow() : p.detection().robots_blue();
      for (const auto& rb : robots) {
        r.by_robot[{team, static_cast<int>(rb.robot_id())}].push_back({rb.x(), rb.y()});
        r.heights.push_back(rb.height());
      }
    }
  }
  return r;
}

double worstDisagreement(const HeightRun& r) {
  double worst = 0;
  int pairs = 0;
  for (const auto& [key, seen] : r.by_robot)
    if (seen.size() == 2) {
      ++pairs;
      worst = std::max(worst, std::hypot(seen[0].first - seen[1].first, seen[0].second - seen[1].second));
    }
  EXPECT_GE(pairs, 3) << "robots seen by both cameras";
  return worst;
}

TEST(RobotHeight, TheTrueHeightBringsPositionsBackToBlobAccuracyAndCamerasAgree) {
  TempDir dir("dv_robot_height");
  const HeightRun wrong = runScene(dir, "");  // the 140 mm default
  const HeightRun right = runScene(dir, "--robot-height 145");
  const HeightRun per_team = runScene(dir, "--robot-height-yellow 145 --robot-height-blue 145");
  EXPECT_LE(right.median_mm, 0.5);
  EXPECT_GT(wrong.median_mm, 2 * right.median_mm);  // the 5 mm error is visible
  EXPECT_LE(worstDisagreement(right), 2.0);
  EXPECT_GT(worstDisagreement(wrong), worstDisagreement(right));
  EXPECT_DOUBLE_EQ(per_team.median_mm, right.median_mm);
  for (double h : right.heights) EXPECT_EQ(h, 145);  // the packets carry the height used
  for (double h : wrong.heights) EXPECT_EQ(h, 140);
}

}  // namespace
}  // namespace dv

// `dotvision run --http` hosts serve's console over its one camera: the
// status lists that camera, snapshots and the pixel-stage layers come, the
// config (run has none) cannot be changed, and a four-point calibration
// accepted with the printed token rebuilds the processor and changes the
// geometry the console shows.
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "geometry/camera_model.h"
#include "geometry/geometry_io.h"
// Last: it brings httplib.
#include "console_suite.h"

namespace dv {
namespace {

using nlohmann::json;

class ConsoleRun : public ConsoleSuite {
 protected:
  static void SetUpTestSuite() { startRun("dv_console_run"); }
};

TEST_F(ConsoleRun, HostsTheConsoleOverItsCamera) {
  ASSERT_FALSE(token_.empty()) << serve_->log();
  json status;
  ASSERT_TRUE(ConsoleServe::waitFor([&] {
    status = getJson("/api/status");
    return status.is_object() && status["cameras"].size() == 1 && status["cameras"][0]["fps_out"].get<double>() > 0;
  })) << status.dump() << serve_->log();
  EXPECT_EQ(status["cameras"][0]["camera_id"], 0);
  EXPECT_EQ(getJson("/api/cameras")["cameras"].size(), 1u);

  auto r = client().Get("/api/cameras/0/snapshot.png?width=400&layer=score,blobs");
  ASSERT_TRUE(r && r->status == 200) << (r ? r->body : "no answer");
  const cv::Mat score = cv::imdecode(std::vector<uchar>(r->body.begin(), r->body.end()), cv::IMREAD_COLOR);
  EXPECT_EQ(score.cols, 400);

  // No config file: changes are refused, with the token too.
  r = client().Patch("/api/config", R"({"robot_heights.default": 130})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  r = client().Patch("/api/config", auth(), R"({"robot_heights.default": 130})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409);
  EXPECT_NE(r->body.find("no config file"), std::string::npos) << r->body;

  // A four-point calibration from where the true camera sees the points.
  r = client().Get("/api/geometry");
  ASSERT_TRUE(r && r->status == 200);
  const Geometry before = geometryFromJson(r->body, "/api/geometry");
  ASSERT_NE(before.camera(0), nullptr);
  const CameraModel truth(*before.camera(0));
  json points = json::array();
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {-4500, 3000}, {-4500, -3000}, {0, 3000}, {0, -3000}, {-3500, 1000}, {-3500, -1000}}) {
    const auto px = truth.fieldToImage({x, y, 0});
    ASSERT_TRUE(px.has_value()) << x << ", " << y;
    points.push_back({x, y, px->u, px->v});
  }
  const json run = finishedRun(0, json{{"points", points}, {"camera_height", 5000}}.dump());
  ASSERT_TRUE(run.is_object());
  ASSERT_TRUE(run["passed"]) << run.dump();
  r = client().Post("/api/cameras/0/calibration/accept", auth(), "{}", "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_NE(r->body.find("its processor uses the new calibration"), std::string::npos) << r->body;
  r = client().Get("/api/geometry");
  ASSERT_TRUE(r && r->status == 200);
  EXPECT_NE(*geometryFromJson(r->body, "/api/geometry").camera(0), *before.camera(0));
  // The camera keeps running on it.
  const uint64_t seen = getJson("/api/status")["cameras"][0]["frames"]["processed"];
  EXPECT_TRUE(ConsoleServe::waitFor([&] {
    const json s = getJson("/api/status");
    return s.is_object() && s["cameras"][0]["frames"]["processed"].get<uint64_t>() > seen + 10;
  }));
}

}  // namespace
}  // namespace dv

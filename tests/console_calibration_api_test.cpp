// Calibration, colors and the log from the console, against a real
// `dotvision serve` on loopback (two synthetic cameras looking straight
// down): a calibration run on a camera's newest frame reports its figures
// and the segments it found, is refused without the token, and once
// accepted is the camera's calibration in /api/geometry while the camera
// keeps detecting; bad hints are refused with their reason; the Colors
// data holds the learned classes and recent blobs; the log holds serve's
// lines.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "geometry/camera_model.h"
#include "geometry/geometry_io.h"
// Last: it brings httplib.
#include "console_suite.h"

namespace dv {
namespace {

using nlohmann::json;
const char* kToken = "calibration-operator-51e2";

class ConsoleCalibration : public ConsoleSuite {
 protected:
  static void SetUpTestSuite() { startServe("dv_console_calib", kToken); }
  static json camera0Calibration() {
    const json g = getJson("/api/geometry");  // kept: a range over a temporary's member dangles
    if (!g.is_object() || !g.contains("calib")) return json();
    for (const json& c : g["calib"])
      if (c["cameraId"] == 0) return c;
    return json();
  }
  static int camera0Robots() {
    const json d = getJson("/api/detections");
    if (!d.is_object()) return -1;
    for (const json& c : d["cameras"])
      if (c["camera_id"] == 0 && c["detection"].is_object()) {
        const json& det = c["detection"];
        return int(det.value("robotsYellow", json::array()).size() + det.value("robotsBlue", json::array()).size());
      }
    return -1;
  }
};

TEST_F(ConsoleCalibration, RunsReportsAndAcceptChangesTheGeometry) {
  ASSERT_TRUE(ConsoleServe::waitFor([] { return camera0Robots() >= 6; }, 120)) << serve_->log();
  const json before = camera0Calibration();
  ASSERT_TRUE(before.is_object()) << getJson("/api/geometry").dump().substr(0, 300) << serve_->log();
  auto c = client();
  const std::string hints = R"({"region": "x<0", "camera_height": 5000})";

  // Without the token nothing starts.
  auto r = c.Post("/api/cameras/0/calibrate", hints, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  EXPECT_EQ(getJson("/api/cameras/0/calibration")["state"], "none");
  // Bad hints are refused with what is wrong.
  r = c.Post("/api/cameras/0/calibrate", auth(), R"({"region": "left"})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("'left'"), std::string::npos) << r->body;
  r = c.Post("/api/cameras/0/calibrate", auth(), R"({"points": [[0, 0, 10, 10]]})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("four or more"), std::string::npos) << r->body;
  r = c.Post("/api/cameras/0/calibrate", auth(), R"({"heigth": 5000})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("'heigth'"), std::string::npos) << r->body;
  r = c.Post("/api/cameras/9/calibrate", auth(), hints, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  // Nothing to accept yet.
  r = c.Post("/api/cameras/0/calibration/accept", auth(), "{}", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409);

  const json run = finishedRun(0, hints);
  ASSERT_TRUE(run.is_object());
  ASSERT_EQ(run["state"], "done") << run.dump();
  EXPECT_TRUE(run["passed"]) << run["report"].dump(1);
  EXPECT_EQ(run["image_size"], json::array({ConsoleServe::kWidth, ConsoleServe::kHeight}));
  EXPECT_GE(run["lines"].size(), 4u);
  const json& report = run["report"];
  EXPECT_TRUE(report["verdict"]["passed"]);
  EXPECT_EQ(report["mode"], "automatic");
  EXPECT_GT(report["measures"]["overlap_ratio"].get<double>(), 0.8);
  // The camera stands 5 m over (-2250, 0).
  const json& pos = report["parameters"]["position_mm"];
  EXPECT_NEAR(pos[0].get<double>(), -2250, 100) << pos.dump();
  EXPECT_NEAR(pos[1].get<double>(), 0, 100) << pos.dump();
  EXPECT_NEAR(pos[2].get<double>(), 5000, 100) << pos.dump();

  // The overlay: the frame calibrated, at the width asked for.
  r = c.Get("/api/cameras/0/calibration/overlay.jpg?width=612");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  const cv::Mat overlay = cv::imdecode(std::vector<uchar>(r->body.begin(), r->body.end()), cv::IMREAD_COLOR);
  EXPECT_EQ(overlay.cols, 612);
  EXPECT_EQ(overlay.rows, 512);

  // Accepting needs the token too; the geometry stays until then.
  r = c.Post("/api/cameras/0/calibration/accept", "{}", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  r = c.Post("/api/cameras/0/calibration/accept", {{"Authorization", "Bearer wrong"}}, "{}", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_EQ(camera0Calibration(), before);

  r = c.Post("/api/cameras/0/calibration/accept", auth(), "{}", "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_NE(r->body.find("the published geometry has the new calibration"), std::string::npos) << r->body;
  const json after = camera0Calibration();
  EXPECT_NE(after, before);
  EXPECT_NEAR(after["focalLength"].get<double>(), report["parameters"]["focal_length_px"].get<double>(), 0.01);
  EXPECT_NEAR(after["derivedCameraWorldTz"].get<double>(), pos[2].get<double>(), 0.5);
  EXPECT_EQ(getJson("/api/cameras/0/calibration")["state"], "accepted");
  // Camera 1 keeps its own.
  // The rebuilt processor keeps detecting the robots in view.
  const uint64_t seen_before = getJson("/api/status")["cameras"][0]["frames"]["processed"];
  EXPECT_TRUE(ConsoleServe::waitFor([&] {
    const json s = getJson("/api/status");
    return s["cameras"][0]["frames"]["processed"].get<uint64_t>() > seen_before + 10 && camera0Robots() >= 6;
  }, 120)) << getJson("/api/detections").dump();
  // Settled: nothing more to accept or reject.
  r = c.Post("/api/cameras/0/calibration/reject", auth(), "{}", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409);
}

TEST_F(ConsoleCalibration, ARejectedRunLeavesTheGeometry) {
  const json before = camera0Calibration();
  auto c = client();
  const json run = finishedRun(1, R"({"region": "x>0", "camera_height": 5000})");
  ASSERT_TRUE(run.is_object());
  ASSERT_EQ(run["state"], "done") << run.dump();
  const json geometry = getJson("/api/geometry");
  auto r = c.Post("/api/cameras/1/calibration/reject", "{}", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  r = c.Post("/api/cameras/1/calibration/reject", auth(), "{}", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(getJson("/api/cameras/1/calibration")["state"], "rejected");
  r = c.Post("/api/cameras/1/calibration/accept", auth(), "{}", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409);
  EXPECT_EQ(getJson("/api/geometry"), geometry);
}

// Four or more known field points clicked where the true camera sees them
// (with its height, as the Calibration page's picker sends them): once
// accepted, every pixel's field point is within 1 mm of the truth's. Points
// that cannot fix a pose are refused at once with the reason.
TEST_F(ConsoleCalibration, PointsFromTheTrueCameraFixItsPose) {
  auto r = client().Get("/api/geometry");
  ASSERT_TRUE(r && r->status == 200);
  const Geometry before = geometryFromJson(r->body, "/api/geometry");
  ASSERT_NE(before.camera(1), nullptr);
  const CameraModel truth(*before.camera(1));  // camera 1's own: no run was accepted for it
  auto clicks = [&](const std::vector<std::pair<double, double>>& field) {
    json points = json::array();
    for (const auto& [x, y] : field) {
      const auto px = truth.fieldToImage({x, y, 0});
      EXPECT_TRUE(px.has_value()) << x << ", " << y;
      if (px) points.push_back({x, y, px->u, px->v});
    }
    return json{{"points", points}, {"camera_height", 5000}}.dump();
  };
  auto c = client();
  // Collinear on the field (the halfway line), and one point given twice: refused at once.
  r = c.Post("/api/cameras/1/calibrate", auth(), clicks({{0, -3000}, {0, -500}, {0, 500}, {0, 3000}}),
             "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("cannot fix a camera pose"), std::string::npos) << r->body;
  r = c.Post("/api/cameras/1/calibrate", auth(), clicks({{0, 3000}, {4500, 3000}, {4500, -3000}, {0, 3000}}),
             "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("cannot fix a camera pose"), std::string::npos) << r->body;
  const std::string good = clicks({{0, 3000}, {0, -3000}, {4500, 3000}, {4500, -3000}, {3500, 1000}, {3500, -1000}});
  r = c.Post("/api/cameras/1/calibrate", good, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);

  const json run = finishedRun(1, good);
  ASSERT_TRUE(run.is_object());
  ASSERT_EQ(run["state"], "done") << run.dump();
  ASSERT_TRUE(run["passed"]) << run["report"].dump(1);
  EXPECT_EQ(run["report"]["mode"], "points");
  r = c.Post("/api/cameras/1/calibration/accept", auth(), "{}", "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  r = c.Get("/api/geometry");
  ASSERT_TRUE(r && r->status == 200);
  const Geometry after = geometryFromJson(r->body, "/api/geometry");
  ASSERT_NE(after.camera(1), nullptr);
  EXPECT_NE(*after.camera(1), *before.camera(1));  // a new calibration, published as floats
  const CameraModel found(*after.camera(1));
  double worst = 0, sum = 0, worst_points = 0;
  int n = 0;
  for (int v = 0; v < ConsoleServe::kHeight; v += 64)
    for (int u = 0; u < ConsoleServe::kWidth; u += 64) {
      const auto a = truth.imageToField({double(u), double(v)}, 0), b = found.imageToField({double(u), double(v)}, 0);
      ASSERT_TRUE(a && b);
      const double e = std::hypot(a->x - b->x, a->y - b->y);
      worst = std::max(worst, e);
      sum += e;
      ++n;
    }
  for (const json& p : json::parse(good)["points"]) {
    const auto b = found.imageToField({p[2].get<double>(), p[3].get<double>()}, 0);
    ASSERT_TRUE(b);
    worst_points = std::max(worst_points, std::hypot(b->x - p[0].get<double>(), b->y - p[1].get<double>()));
  }
  const json& pos = run["report"]["parameters"]["position_mm"];
  std::printf("points: field error over camera 1's image mean %.3f mm, largest %.3f mm; at the points %.3f mm; "
              "position %s\n", sum / n, worst, worst_points, pos.dump().c_str());
  EXPECT_LT(sum / n, 1.0) << "mm, the mean field error over the image";
  EXPECT_LT(worst_points, 1.0) << "mm, at the points given";
}

TEST_F(ConsoleCalibration, ColorsHoldTheLearnedClassesAndRecentBlobs) {
  json j;
  ASSERT_TRUE(ConsoleServe::waitFor([&] {
    j = getJson("/api/cameras/0/colors");
    return j.is_object() && j["classes"].is_object() && j["blobs"].size() > 20;
  }, 120)) << j.dump();
  for (const char* name : {"yellow", "blue", "green", "pink", "orange", "field", "white"}) {
    ASSERT_TRUE(j["classes"].contains(name)) << j["classes"].dump();
    double sum = 0;
    for (const json& v : j["classes"][name]) sum += v.get<double>();
    EXPECT_GT(sum, 200) << name << " " << j["classes"][name].dump();  // chromaticity: ~300 less the dark offset
  }
  // Both teams are in view: yellow and blue are well apart.
  EXPECT_GT(j["separations"]["yellow_blue"].get<double>(), 30) << j["separations"].dump();
  EXPECT_LE(j["blobs"].size(), 600u);
  for (const json& b : j["blobs"]) ASSERT_EQ(b.size(), 4u);
}

TEST_F(ConsoleCalibration, TheLogHoldsServesLinesAndNotTheToken) {
  json j;
  ASSERT_TRUE(ConsoleServe::waitFor([&] {
    j = getJson("/api/log");
    return j.is_object() && j["lines"].dump().find("running 2 camera(s)") != std::string::npos;
  }, 60)) << j.dump();
  uint64_t last = 0;
  for (const json& l : j["lines"]) {
    EXPECT_GT(l["seq"].get<uint64_t>(), last);
    last = l["seq"];
  }
  EXPECT_EQ(j["lines"].dump().find(kToken), std::string::npos);
  EXPECT_TRUE(getJson("/api/log?after=" + std::to_string(last))["lines"].empty() ||
              getJson("/api/log?after=" + std::to_string(last))["lines"][0]["seq"].get<uint64_t>() > last);
  auto r = client().Get("/api/log?after=x");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
}

}  // namespace
}  // namespace dv

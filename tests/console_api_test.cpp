// The console's JSON API against a real `dotvision serve` on loopback: the
// status, cameras, detections and geometry a script reads; snapshots of the
// size asked for, with their layers; refusal of every change without the
// operator's token (401) or with a wrong one (403), the running config
// untouched; a change with the token reaching the processor (the heights in
// the status records) and, only when asked, the file with its comments; a
// broken config refused with its errors, the old one kept.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "dotvision/ssl_geometry.pb.h"
#include "geometry/proto_json.h"
// Last: it brings httplib.
#include "console_suite.h"

namespace dv {
namespace {

using nlohmann::json;
const char* kToken = "field-a-operator-7f3c";

class ConsoleApi : public ConsoleSuite {
 protected:
  static void SetUpTestSuite() { startServe("dv_console_api", kToken); }
  // -1 while the status cannot be had (a request timing out on a loaded machine).
  static double heightInUse() {
    const json s = getJson("/api/status");
    if (!s.is_object() || !s.contains("cameras") || s["cameras"].empty()) return -1;
    const json& h = s["cameras"][0]["robot_height_mm"]["yellow"];
    return h.is_number() ? h.get<double>() : -1;
  }
};

TEST_F(ConsoleApi, StatusCamerasDetectionsAndGeometry) {
  const json status = liveStatus();
  ASSERT_EQ(status["cameras"].size(), 2u) << status.dump() << serve_->log();
  EXPECT_EQ(status["config"], serve_->configPath());
  for (const json& c : status["cameras"]) {
    // Ok, or behind while a loaded machine starts both cameras; never lost.
    EXPECT_TRUE(c["health"] == "ok" ||
                (c["health"] == "degraded" &&
                 c["health_reason"].get<std::string>().find("behind") != std::string::npos))
        << c.dump();
    EXPECT_TRUE(c["latency"]["total"]["p99_ms"].is_number());
    EXPECT_TRUE(c["frames"]["dropped"].is_number());
    // The white lines' color (the camera's cast) and no color warning: the
    // scene shows both teams and the ball.
    EXPECT_EQ(c["colors"]["issues"], "") << c.dump();
    ASSERT_TRUE(c["colors"]["lines_rgb"].is_array()) << c.dump();
    EXPECT_GT(c["colors"]["lines_rgb"][1].get<double>(), 150) << c.dump();
  }
  // The printed line says where the token is, not what it is.
  EXPECT_EQ(serve_->printedToken(), "");
  EXPECT_EQ(serve_->log().find(kToken), std::string::npos);

  const json cams = getJson("/api/cameras");
  ASSERT_EQ(cams["cameras"].size(), 2u) << cams.dump();
  EXPECT_EQ(cams["cameras"][0]["image_width"], ConsoleServe::kWidth);
  // Camera 0 hangs over x = -2250 and sees about 3 m either way along x.
  ASSERT_GE(cams["cameras"][0]["footprint"].size(), 8u);
  double x_min = 1e9, x_max = -1e9;
  for (const json& p : cams["cameras"][0]["footprint"]) {
    x_min = std::min(x_min, p[0].get<double>());
    x_max = std::max(x_max, p[0].get<double>());
  }
  EXPECT_NEAR(x_min, -5250, 300);
  EXPECT_NEAR(x_max, 750, 300);

  // Detections come once asked for: the scene's robots in camera 0.
  json cam0, last;
  ASSERT_TRUE(ConsoleServe::waitFor(
      [&] {
        last = getJson("/api/detections");
        if (!last.is_object() || last["cameras"].size() != 2) return false;
        cam0 = last["cameras"][0];
        return !cam0["detection"].is_null();
      },
      120))
      << last.dump() << serve_->log();
  EXPECT_EQ(cam0["camera_id"], 0);
  const json& d = cam0["detection"];
  const size_t robots = d.value("robotsYellow", json::array()).size() + d.value("robotsBlue", json::array()).size();
  // Those placed in its view, and maybe some of camera 1's in the overlap.
  EXPECT_GE(robots, size_t(ConsoleServe::kCamera0Robots - 1)) << d.dump();
  EXPECT_GT(d["tCapture"].get<double>(), 1.6e9);  // Unix seconds

  auto g = client().Get("/api/geometry");
  ASSERT_TRUE(g && g->status == 200);
  ssl::SSL_GeometryData geometry;
  parseCanonicalJson(g->body, geometry, "/api/geometry");
  EXPECT_EQ(geometry.calib_size(), 2);
  EXPECT_EQ(geometry.field().field_length(), 9000);

  // The field point under the image center of camera 0 is below the camera.
  const json p = getJson("/api/cameras/0/field_point?u=612&v=512");
  EXPECT_NEAR(p["x"].get<double>(), -2250, 100) << p.dump();
  EXPECT_NEAR(p["y"].get<double>(), 0, 100) << p.dump();
}

TEST_F(ConsoleApi, SnapshotsHaveTheSizeAskedForAndTheirLayers) {
  liveStatus();
  auto raw = client().Get("/api/cameras/0/snapshot.png?width=400");
  ASSERT_TRUE(raw && raw->status == 200) << (raw ? raw->body : "no answer");
  EXPECT_EQ(raw->get_header_value("Content-Type"), "image/png");
  const cv::Mat a = cv::imdecode(std::vector<uchar>(raw->body.begin(), raw->body.end()), cv::IMREAD_COLOR);
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a.cols, 400);
  EXPECT_EQ(a.rows, 335);  // 1024 * 400 / 1224, rounded
  auto drawn = client().Get("/api/cameras/0/snapshot.png?width=400&layer=raw,lines,detections");
  ASSERT_TRUE(drawn && drawn->status == 200);
  const cv::Mat b = cv::imdecode(std::vector<uchar>(drawn->body.begin(), drawn->body.end()), cv::IMREAD_COLOR);
  ASSERT_EQ(b.size(), a.size());
  // The field lines are drawn in magenta, which the camera image never has.
  auto magenta = [](const cv::Mat& m) {
    int n = 0;
    for (int y = 0; y < m.rows; ++y)
      for (int x = 0; x < m.cols; ++x) {
        const cv::Vec3b px = m.at<cv::Vec3b>(y, x);
        n += px[0] > 200 && px[2] > 200 && px[1] < 80;
      }
    return n;
  };
  EXPECT_EQ(magenta(a), 0);
  EXPECT_GT(magenta(b), 500);
  auto jpg = client().Get("/api/cameras/1/snapshot.jpg");
  ASSERT_TRUE(jpg && jpg->status == 200);
  EXPECT_EQ(jpg->get_header_value("Content-Type"), "image/jpeg");
  const cv::Mat c = cv::imdecode(std::vector<uchar>(jpg->body.begin(), jpg->body.end()), cv::IMREAD_COLOR);
  EXPECT_EQ(c.cols, 960);  // the default width

  auto layer = client().Get("/api/cameras/0/snapshot.png?layer=chroma2");
  ASSERT_TRUE(layer);
  EXPECT_EQ(layer->status, 400);
  EXPECT_NE(layer->body.find("unknown layer 'chroma2'"), std::string::npos) << layer->body;
  auto width = client().Get("/api/cameras/0/snapshot.png?width=wide");
  ASSERT_TRUE(width);
  EXPECT_EQ(width->status, 400);
  auto none = client().Get("/api/cameras/7/snapshot.png");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 404);
  EXPECT_NE(none->body.find("no camera 7"), std::string::npos) << none->body;
}

// The pixel-stage layers come from the console's own pipeline run: each is
// a picture of the rectified grid at the width asked for, and each shows what
// its stage makes of the frame; the grid maps cells to field mm (the robots
// the camera reports lie on peaks of the score picture there).
TEST_F(ConsoleApi, PixelStageLayersAreTheConsolesOwnPipelineRun) {
  liveStatus();
  const json grid = getJson("/api/cameras/0/grid");
  ASSERT_TRUE(grid.is_object() && grid["width"].get<int>() > 400) << grid.dump() << serve_->log();
  const int gw = grid["width"], gh = grid["height"];
  const double x0 = grid["x0_mm"], y0 = grid["y0_mm"], mm = grid["mm_per_cell"];
  // Camera 0 looks down at (-2250, 0): the grid's middle.
  EXPECT_NEAR(x0 + mm * (gw - 1) / 2, -2250, 300) << grid.dump();
  EXPECT_NEAR(y0 - mm * (gh - 1) / 2, 0, 300) << grid.dump();
  EXPECT_EQ(grid["plane_height_mm"], 150) << grid.dump();

  auto picture = [](const std::string& layers, int width) {
    auto r = client().Get(("/api/cameras/0/snapshot.png?width=" + std::to_string(width) + "&layer=" + layers).c_str());
    if (!r || r->status != 200) {
      ADD_FAILURE() << layers << ": " << (r ? r->body : "no answer");
      return cv::Mat();
    }
    return cv::imdecode(std::vector<uchar>(r->body.begin(), r->body.end()), cv::IMREAD_COLOR);
  };
  std::map<std::string, cv::Mat> seen;
  for (const char* name : {"rectified", "chroma", "gradient", "score"}) {
    const cv::Mat m = picture(name, 400);
    ASSERT_FALSE(m.empty()) << name;
    EXPECT_EQ(m.cols, 400) << name;
    EXPECT_NEAR(m.rows, double(gh) * 400 / gw, 1) << name;
    seen[name] = m;
  }
  const cv::Scalar carpet = cv::mean(seen["rectified"]);
  EXPECT_GT(carpet[1], carpet[2] + 10) << "a green carpet: " << carpet;  // BGR
  // Chroma: the colors divided by their brightness, a gray at 128 each.
  const cv::Scalar chroma = cv::mean(seen["chroma"]);
  EXPECT_GT(chroma[0] + chroma[1] + chroma[2], 300) << chroma;
  EXPECT_GT(cv::norm(seen["rectified"], seen["chroma"], cv::NORM_L1) / seen["chroma"].total(), 30);
  // Gradient and score are gray about 128 (zero) with bright peaks at the blobs.
  for (const char* name : {"gradient", "score"}) {
    std::vector<cv::Mat> ch;
    cv::split(seen[name], ch);
    EXPECT_EQ(cv::norm(ch[0], ch[2], cv::NORM_INF), 0) << name << " is gray";
    cv::Mat mid;
    cv::inRange(ch[0], 118, 138, mid);
    EXPECT_GT(cv::countNonZero(mid), 0.5 * mid.total()) << name;
    double top = 0;
    cv::minMaxLoc(ch[0], nullptr, &top);
    EXPECT_GT(top, 200) << name;
  }
  EXPECT_GT(cv::norm(seen["gradient"], seen["score"], cv::NORM_L1) / seen["score"].total(), 3);
  // Blobs: white rings where the pixel stage found them.
  auto white = [](const cv::Mat& m) {
    cv::Mat w;
    cv::inRange(m, cv::Scalar(230, 230, 230), cv::Scalar(255, 255, 255), w);
    return cv::countNonZero(w);
  };
  const cv::Mat score_blobs = picture("score,blobs", 400);
  ASSERT_EQ(score_blobs.size(), seen["score"].size());
  EXPECT_GT(white(score_blobs), white(seen["score"]) + 200);
  EXPECT_GT(white(picture("raw,blobs", 400)), white(picture("raw", 400)) + 200);

  // Each robot camera 0 reports stands on a peak of the full-size score picture.
  const cv::Mat score = picture("score", gw);
  ASSERT_EQ(score.cols, gw);
  json det;
  ASSERT_TRUE(ConsoleServe::waitFor([&] {
    const json d = getJson("/api/detections");
    if (d.is_object() && d["cameras"][0]["detection"].is_object()) det = d["cameras"][0]["detection"];
    return det.is_object();
  }));
  int robots = 0;
  for (const char* team : {"robotsYellow", "robotsBlue"})
    for (const json& r : det.value(team, json::array())) {
      const int gx = int(std::lround((r["x"].get<double>() - x0) / mm));
      const int gy = int(std::lround((y0 - r["y"].get<double>()) / mm));
      ASSERT_TRUE(gx >= 3 && gy >= 3 && gx < gw - 3 && gy < gh - 3) << r.dump();
      double peak = 0;
      cv::minMaxLoc(score(cv::Rect(gx - 3, gy - 3, 7, 7)), nullptr, &peak);
      EXPECT_GT(peak, 128 + 127 * 0.24 / (4 * 0.24)) << "no blob at grid (" << gx << ", " << gy << ") for " << r.dump();
      ++robots;
    }
  EXPECT_GE(robots, ConsoleServe::kCamera0Robots - 1);

  auto r = client().Get("/api/cameras/0/snapshot.png?layer=score,rectified");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("both pictures"), std::string::npos) << r->body;
  r = client().Get("/api/cameras/7/grid");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
}

TEST_F(ConsoleApi, ChangesNeedTheTokenAndGoTheReloadWay) {
  liveStatus();
  const std::string original = serve_->configText();
  ASSERT_TRUE(ConsoleServe::waitFor([] { return heightInUse() == 140; })) << getJson("/api/status").dump();

  // Without a token: 401; with a wrong one: 403. Nothing changes.
  const std::string patch = R"({"robot_heights.default": 130})";
  auto c = client();
  auto r = c.Patch("/api/config", patch, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  EXPECT_NE(r->body.find("needs the operator's token"), std::string::npos) << r->body;
  r = c.Put("/api/config?save=1", "cameras: []\n", "application/yaml");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  r = c.Patch("/api/config", {{"Authorization", "Bearer not-the-token"}}, patch, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  r = c.Patch("/api/config", {{"X-Dotvision-Token", std::string(kToken) + "x"}}, patch, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  std::this_thread::sleep_for(std::chrono::seconds(2));
  EXPECT_EQ(heightInUse(), 140);
  EXPECT_EQ(serve_->configText(), original);
  EXPECT_EQ(client().Get("/api/config")->body, original);

  // With the token: applied to the processors, the file untouched.
  r = c.Patch("/api/config", auth(), patch, "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  json answer = json::parse(r->body);
  EXPECT_TRUE(answer["applied"]);
  EXPECT_FALSE(answer["saved"]);
  EXPECT_TRUE(answer["layout_kept"]);
  EXPECT_NE(answer["notes"].dump().find("yellow 130.0 mm"), std::string::npos) << r->body;
  EXPECT_TRUE(ConsoleServe::waitFor([] { return heightInUse() == 130; }));
  EXPECT_EQ(serve_->configText(), original);
  EXPECT_NE(client().Get("/api/config")->body.find("default: 130   # the league's usual"), std::string::npos);

  // A broken config is refused with the error naming the file and line; the running one stays.
  r = c.Put("/api/config", auth(), "cameras:\n  - id: 0\n    sorce: x\n", "application/yaml");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  answer = json::parse(r->body);
  EXPECT_FALSE(answer["applied"]);
  EXPECT_NE(answer["error"].get<std::string>().find(serve_->configPath() + ":3"), std::string::npos) << r->body;
  EXPECT_NE(answer["error"].get<std::string>().find("did you mean 'source'?"), std::string::npos) << r->body;
  r = c.Patch("/api/config", auth(), R"({"robot_heights.default": 500})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("robot_heights.default"), std::string::npos) << r->body;
  r = c.Patch("/api/config", auth(), "[1, 2]", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  std::this_thread::sleep_for(std::chrono::seconds(1));
  EXPECT_EQ(heightInUse(), 130);

  // Saved when asked: the file gets the edit and keeps its comments.
  r = c.Patch("/api/config?save=1", auth(), R"({"robot_heights.default": 135})",
              "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_TRUE(json::parse(r->body)["saved"]);
  const std::string saved = serve_->configText();
  EXPECT_NE(saved.find("default: 135   # the league's usual"), std::string::npos) << saved;
  EXPECT_TRUE(ConsoleServe::waitFor([] { return heightInUse() == 135; }));
}

// Every thread of serve with its name and nice value, from /proc.
std::multimap<std::string, int> threadNiceByName(pid_t pid) {
  std::multimap<std::string, int> out;
  const std::string dir = "/proc/" + std::to_string(pid) + "/task";
  for (const auto& task : std::filesystem::directory_iterator(dir)) {
    std::ifstream comm(task.path() / "comm"), stat(task.path() / "stat");
    std::string name, text;
    std::getline(comm, name);
    std::getline(stat, text);
    // Field 19 is the nice value; fields start after the ")" that ends the name.
    std::istringstream rest(text.substr(text.rfind(')') + 2));
    std::string field;
    for (int i = 3; i <= 19 && rest >> field; ++i) {
    }
    out.emplace(name, std::stoi(field));
  }
  return out;
}

TEST_F(ConsoleApi, ConsoleThreadsGiveWayToTheCameras) {
  // Requests until an HTTP thread has served one and both cameras run (a
  // loaded machine may take a while).
  std::multimap<std::string, int> threads;
  for (int i = 0; i < 60; ++i) {
    getJson("/api/status");
    threads = threadNiceByName(serve_->pid());
    int d = 0;
    for (const auto& t : threads) d += t.first.rfind("detect ", 0) == 0;
    if (threads.count("console") > 0 && d == 2) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  int console = 0, detect = 0;
  for (const auto& [name, nice] : threads) {
    if (name == "console") {
      ++console;
      EXPECT_EQ(nice, 10) << "an HTTP thread of the console";
    }
    if (name.rfind("detect ", 0) == 0) {
      ++detect;
      EXPECT_EQ(nice, 0) << name;
    }
  }
  EXPECT_GE(console, 1);
  EXPECT_EQ(detect, 2) << "one detection thread per camera";
}

}  // namespace
}  // namespace dv

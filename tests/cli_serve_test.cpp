// `dotvision serve` as an operator runs it: a site config validated with
// --check, every config error naming file, line and key; a live run on
// loopback multicast whose packets carry Unix time; the game controller's
// team names changing the robot heights at the next frames; SIGHUP with a
// broken file keeping the old config, with a good one applying new heights
// without a restart; SIGTERM ending with the summary.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "dotvision/ssl_referee.pb.h"
#include "dotvision/ssl_wrapper.pb.h"
#include "geometry/geometry_io.h"
#include "geometry/proto_json.h"
#include "net/multicast.h"
#include "cli_process.h"
#include "temp_dir.h"

namespace dv {
namespace {

TEST(ServeCheck, TheExampleIsValidAndErrorsNameFileLineAndKey) {
  std::string out;
  EXPECT_EQ(runCli("serve --check " + std::string(DV_SOURCE_DIR) + "/config/site.example.yaml", out), 0) << out;
  EXPECT_NE(out.find("valid"), std::string::npos) << out;
  TempDir dir("dv_serve_check");
  std::ofstream(dir.file("bad.yaml")) << "cameras:\n  - id: 0\n    source: synthetic://default/0\n    treads: 2\n";
  EXPECT_EQ(runCli("serve --check " + dir.file("bad.yaml"), out), 2) << out;
  EXPECT_NE(out.find("bad.yaml:4"), std::string::npos) << out;
  EXPECT_NE(out.find("cameras[0].treads"), std::string::npos) << out;
}

// One 1224 x 1024 camera over a Division B half with both teams in view.
const char* kScene = R"(name: serve_test
seed: 3
field: division_b
cameras:
  - {id: 0, position: [-2250, 0, 5000], look_at: [-2250, 0, 0], up: [-1, 0, 0], focal_length: 875, distortion: 0.03, size: [1224, 1024]}
random_robots: {yellow: 4, blue: 4, camera: 0, margin_px: 80}
ball: {position: [-1800, 400]}
frames: 1
)";

std::string siteConfig(const std::string& scene, int vision_port, int referee_port, double default_height,
                       const std::string& tail = "") {
  std::ostringstream s;
  s << "cameras:\n  - id: 0\n    source: synthetic://" << scene << "/0\n    threads: 1\n    backend: cpu\n"
    << "network:\n  vision: {group: 224.5.23.2, port: " << vision_port << ", interface: 127.0.0.1}\n"
    << "  referee: {enabled: true, group: 224.5.23.1, port: " << referee_port << "}\n"
    << "robot_heights:\n  default: " << default_height << "\n  teams: {ER-Force: 150}\n" << tail
    << "status_interval: 0\n";
  return s.str();
}

class ServeLive : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_.file("scene.yaml")) << kScene;
    vision_port_ = 42000 + ::getpid() % 1000;
    referee_port_ = vision_port_ + 1000;
    config_ = dir_.file("site.yaml");
    std::ofstream(config_) << siteConfig(dir_.file("scene.yaml"), vision_port_, referee_port_, 140);
  }
  void TearDown() override {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  void start() { pid_ = spawnCli({"serve", config_}, dir_.file("serve.log")); }
  // Yellow and blue heights of the next detection packet with both teams, within timeout.
  bool nextHeights(MulticastReceiver& rx, double& yellow, double& blue, double& t_capture, double timeout_s = 30) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    std::string payload;
    while (std::chrono::steady_clock::now() < until) {
      if (!rx.receive(0.5, payload)) continue;
      ssl::SSL_WrapperPacket p;
      if (!p.ParseFromString(payload) || !p.has_detection()) continue;
      const auto& d = p.detection();
      if (d.robots_yellow_size() == 0 || d.robots_blue_size() == 0) continue;
      yellow = d.robots_yellow(0).height();
      blue = d.robots_blue(0).height();
      t_capture = d.t_capture();
      return true;
    }
    return false;
  }
  // Waits until packets carry these heights (the change applies from the next frame on).
  bool waitForHeights(MulticastReceiver& rx, double want_yellow, double want_blue, double timeout_s = 20) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    double y = 0, b = 0, t = 0;
    while (std::chrono::steady_clock::now() < until)
      if (nextHeights(rx, y, b, t, 2) && y == want_yellow && b == want_blue) return true;
    ADD_FAILURE() << "last heights: yellow " << y << ", blue " << b;
    return false;
  }

  TempDir dir_{"dv_serve_live"};
  int vision_port_ = 0, referee_port_ = 0;
  std::string config_;
  pid_t pid_ = -1;
};

ssl::Referee refereePacket(const std::string& yellow, const std::string& blue) {
  ssl::Referee r;
  r.set_packet_timestamp(1700000000000000ull);
  r.set_stage(ssl::Referee::NORMAL_FIRST_HALF);
  r.set_command(ssl::Referee::STOP);
  r.set_command_counter(1);
  r.set_command_timestamp(1700000000000000ull);
  for (auto [team, name] : {std::pair{r.mutable_yellow(), yellow}, std::pair{r.mutable_blue(), blue}}) {
    team->set_name(name);
    team->set_score(0);
    team->set_red_cards(0);
    team->set_yellow_cards(0);
    team->set_timeouts(4);
    team->set_timeout_time(300000000);
    team->set_goalkeeper(0);
  }
  return r;
}

TEST_F(ServeLive, RefereeTeamsReloadAndStopAllTakeEffectWhileRunning) {
  MulticastReceiver rx("224.5.23.2", static_cast<uint16_t>(vision_port_), "127.0.0.1");
  MulticastSender referee("224.5.23.1", static_cast<uint16_t>(referee_port_), "127.0.0.1");
  start();
  double y = 0, b = 0, t = 0;
  ASSERT_TRUE(nextHeights(rx, y, b, t, 60)) << readAll(dir_.file("serve.log"));
  EXPECT_EQ(y, 140);
  EXPECT_EQ(b, 140);
  const double now = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  EXPECT_NEAR(t, now, 5);  // Unix seconds

  // The game controller names the teams: yellow is in the table (any case), blue is not.
  const std::string gc = refereePacket("er-force", "Unknown Bots").SerializeAsString();
  for (int i = 0; i < 5; ++i) referee.send(gc);
  EXPECT_TRUE(waitForHeights(rx, 150, 140));

  // A broken file is refused; the running config stays and packets keep coming.
  std::ofstream(config_) << "cameras: [\n";
  ::kill(pid_, SIGHUP);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_TRUE(waitForHeights(rx, 150, 140));
  // A good one applies new heights without a restart.
  std::ofstream(config_) << siteConfig(dir_.file("scene.yaml"), vision_port_, referee_port_, 130,
                                       "  blue: 135\n");
  ::kill(pid_, SIGHUP);
  EXPECT_TRUE(waitForHeights(rx, 150, 135));
  // A new vision port: the packets move there without a restart.
  MulticastReceiver moved("224.5.23.2", static_cast<uint16_t>(vision_port_ + 500), "127.0.0.1");
  std::ofstream(config_) << siteConfig(dir_.file("scene.yaml"), vision_port_ + 500, referee_port_, 130,
                                       "  blue: 135\n");
  ::kill(pid_, SIGHUP);
  EXPECT_TRUE(waitForHeights(moved, 150, 135));

  ::kill(pid_, SIGTERM);
  EXPECT_EQ(waitExit(pid_), 0);
  pid_ = -1;
  const std::string log = readAll(dir_.file("serve.log"));
  EXPECT_NE(log.find("reload refused, the running config stays"), std::string::npos) << log;
  EXPECT_NE(log.find("team \"Unknown Bots\" (blue) is not in the team height table"), std::string::npos) << log;
  EXPECT_NE(log.find("stopped by a signal"), std::string::npos) << log;
  EXPECT_NE(log.find("camera 0: "), std::string::npos) << log;
}

// The raw ring: SIGUSR1 writes the last second of frames with their
// detections, and `run` on that folder finds the same robots and balls at
// the same places (bit for bit: the same frames, time stamps and the
// published single-precision geometry). The tracker's history from before
// the dump is not in it, so the first frames' confidences may differ.
TEST_F(ServeLive, RawFramesWrittenOnSigusr1ReplayToTheSameDetections) {
  std::ofstream(config_) << siteConfig(dir_.file("scene.yaml"), vision_port_, referee_port_, 140,
                                       "record: {raw_dir: " + dir_.file("dumps") +
                                           ", raw_seconds: 0.5, on_health_change: false}\n");
  MulticastReceiver rx("224.5.23.2", static_cast<uint16_t>(vision_port_), "127.0.0.1");
  start();
  double y = 0, b = 0, t = 0;
  ASSERT_TRUE(nextHeights(rx, y, b, t, 60)) << readAll(dir_.file("serve.log"));
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ::kill(pid_, SIGUSR1);
  std::string dump;
  for (int i = 0; i < 200 && dump.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const std::string log = readAll(dir_.file("serve.log"));
    const size_t at = log.find("frames in ");
    if (at != std::string::npos && log.find(';', at) != std::string::npos)
      dump = log.substr(at + 10, log.find(';', at) - at - 10);
  }
  ASSERT_FALSE(dump.empty()) << readAll(dir_.file("serve.log"));
  std::string out;
  ASSERT_EQ(runCli("run --source " + dump + " --geometry " + dump + "/geometry.json --camera-id 0 --no-publish "
                   "--jsonl " + dir_.file("replay.jsonl"), out), 0) << out;
  std::ifstream live_in(dump + "/detections.jsonl"), replay_in(dir_.file("replay.jsonl"));
  std::string a, c;
  int frames = 0;
  while (std::getline(live_in, a)) {
    ASSERT_TRUE(std::getline(replay_in, c)) << "replay has fewer frames";
    ssl::SSL_WrapperPacket pa, pc;
    parseCanonicalJson(a, pa, "live");
    parseCanonicalJson(c, pc, "replay");
    ssl::SSL_DetectionFrame da = pa.detection(), dc = pc.detection();
    EXPECT_EQ(da.frame_number(), dc.frame_number());
    EXPECT_EQ(da.t_capture(), dc.t_capture());
    ASSERT_EQ(da.robots_yellow_size(), dc.robots_yellow_size());
    ASSERT_EQ(da.robots_blue_size(), dc.robots_blue_size());
    ASSERT_EQ(da.balls_size(), dc.balls_size());
    for (int i = 0; i < da.robots_yellow_size(); ++i) {
      EXPECT_EQ(da.robots_yellow(i).x(), dc.robots_yellow(i).x());
      EXPECT_EQ(da.robots_yellow(i).y(), dc.robots_yellow(i).y());
    }
    for (int i = 0; i < da.balls_size(); ++i) EXPECT_EQ(da.balls(i).x(), dc.balls(i).x());
    if (frames >= 3) {  // past the tracker's start: everything but the send time
      da.set_t_sent(0);  // when it went out, and the camera's own clock, are no detections
      dc.set_t_sent(0);
      da.clear_t_capture_camera();
      dc.clear_t_capture_camera();
      EXPECT_EQ(da.SerializeAsString(), dc.SerializeAsString()) << "frame " << da.frame_number();
    }
    ++frames;
  }
  // Half a second at 60 fps, less what a loaded machine dropped (14 seen
  // with the suite running beside it): enough frames past the tracker's
  // start to compare whole.
  EXPECT_GE(frames, 8);
}

// One camera that cannot start does not stop the others; with
// `geometry: {source: publish}` the in-process geometry publisher sends the
// field and the calibrations on the vision group.
TEST_F(ServeLive, ABadCameraIsReportedAndTheOthersRunWithTheGeometryPublished) {
  std::string out;
  ASSERT_EQ(runCli("synth " + dir_.file("scene.yaml") + " --out " + dir_.file("scene_out"), out), 0) << out;
  std::ostringstream cfg;
  cfg << "cameras:\n"
      << "  - {id: 0, source: \"synthetic://" << dir_.file("scene.yaml") << "/0\", threads: 1, backend: cpu}\n"
      << "  - {id: 1, source: " << dir_.file("no_such_folder") << "}\n"
      << "network:\n  vision: {group: 224.5.23.2, port: " << vision_port_ << ", interface: 127.0.0.1}\n"
      << "  geometry: {source: publish, file: " << dir_.file("scene_out/geometry.json") << "}\n"
      << "  referee: {enabled: false}\n"
      << "status_interval: 0\n";
  std::ofstream(config_) << cfg.str();
  MulticastReceiver rx("224.5.23.2", static_cast<uint16_t>(vision_port_), "127.0.0.1");
  start();
  bool geometry = false, detection = false;
  std::string payload;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < until && !(geometry && detection)) {
    if (!rx.receive(0.5, payload)) continue;
    ssl::SSL_WrapperPacket p;
    if (!p.ParseFromString(payload)) continue;
    if (p.has_geometry() && p.geometry().calib_size() >= 1) geometry = true;
    if (p.has_detection() && p.detection().camera_id() == 0) {
      detection = true;
      EXPECT_TRUE(p.detection().has_t_capture_camera());  // the camera's own clock rides along
    }
  }
  EXPECT_TRUE(geometry);
  EXPECT_TRUE(detection);
  ::kill(pid_, SIGTERM);
  EXPECT_EQ(waitExit(pid_), 0);
  pid_ = -1;
  const std::string log = readAll(dir_.file("serve.log"));
  EXPECT_NE(log.find("camera 1 (" + config_ + ":"), std::string::npos) << log;  // names the file and line
  EXPECT_NE(log.find("not started"), std::string::npos) << log;
  EXPECT_NE(log.find("running 1 camera(s)"), std::string::npos) << log;
}

// The geometry file changes under a running serve to a camera of another
// size: SIGHUP rebuilds the camera's tables for it, the frames that no longer
// fit are skipped and counted without a crash, and the old file brought back
// brings the detections back.
TEST_F(ServeLive, AGeometryFileWithAnotherCameraSizeIsTakenOnSighupWithoutACrash) {
  std::string out;
  ASSERT_EQ(runCli("synth " + dir_.file("scene.yaml") + " --out " + dir_.file("scene_out"), out), 0) << out;
  const std::string geometry_file = dir_.file("geometry.json");
  const Geometry original = loadGeometry(dir_.file("scene_out/geometry.json"));
  saveGeometry(original, geometry_file);
  std::ostringstream cfg;
  cfg << "cameras:\n  - {id: 0, source: \"synthetic://" << dir_.file("scene.yaml") << "/0\", threads: 1, backend: cpu}\n"
      << "network:\n  vision: {group: 224.5.23.2, port: " << vision_port_ << ", interface: 127.0.0.1}\n"
      << "  geometry: {source: file, file: " << geometry_file << "}\n"
      << "  referee: {enabled: false}\n"
      << "status_interval: 0\n";
  std::ofstream(config_) << cfg.str();
  MulticastReceiver rx("224.5.23.2", static_cast<uint16_t>(vision_port_), "127.0.0.1");
  auto detectionWithin = [&](double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    std::string payload;
    while (std::chrono::steady_clock::now() < until) {
      ssl::SSL_WrapperPacket p;
      if (rx.receive(0.2, payload) && p.ParseFromString(payload) && p.has_detection()) return true;
    }
    return false;
  };
  auto logHas = [&](const std::string& text) {
    for (int i = 0; i < 200; ++i, std::this_thread::sleep_for(std::chrono::milliseconds(100)))
      if (readAll(dir_.file("serve.log")).find(text) != std::string::npos) return true;
    return false;
  };
  start();
  ASSERT_TRUE(detectionWithin(60)) << readAll(dir_.file("serve.log"));

  // The same view from a camera of twice the resolution.
  Geometry bigger = original;
  CameraCalibration& c = bigger.cameras.at(0);
  c.image_width *= 2;
  c.image_height *= 2;
  c.focal_length *= 2;
  c.principal_point_x = 2 * c.principal_point_x + 0.5;
  c.principal_point_y = 2 * c.principal_point_y + 0.5;
  saveGeometry(bigger, geometry_file);
  ::kill(pid_, SIGHUP);
  EXPECT_TRUE(logHas("camera 0: new calibration from " + geometry_file + " (2448 x 2048 px)")) << readAll(dir_.file("serve.log"));
  EXPECT_TRUE(logHas("every such frame is skipped and counted")) << readAll(dir_.file("serve.log"));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  while (rx.receive(0.05, out)) {
  }
  EXPECT_FALSE(detectionWithin(1.0)) << "1224 x 1024 frames measured through a 2448 x 2048 calibration";
  ASSERT_EQ(::kill(pid_, 0), 0) << "serve is gone";

  saveGeometry(original, geometry_file);
  ::kill(pid_, SIGHUP);
  EXPECT_TRUE(logHas("(1224 x 1024 px)")) << readAll(dir_.file("serve.log"));
  EXPECT_TRUE(detectionWithin(30)) << readAll(dir_.file("serve.log"));
  ::kill(pid_, SIGTERM);
  EXPECT_EQ(waitExit(pid_), 0);
  pid_ = -1;
}

}  // namespace
}  // namespace dv

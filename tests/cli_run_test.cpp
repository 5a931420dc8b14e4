// The `run`, `eval` and `bench` command contract, exercised through the built
// binary on real files: exit codes, outputs, and one clear message per bad
// input (naming the file or frame) while the run goes on where it can.
#include <chrono>
#include <gtest/gtest.h>

#include <algorithm>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>

#include "core/error.h"
#include "dotvision/ssl_wrapper.pb.h"
#include "eval/detection_files.h"
#include "geometry/proto_json.h"
#include "net/multicast.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

struct CliResult {
  int code = -1;
  std::string out, err;
};

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string l;
  while (std::getline(ss, l))
    if (!l.empty()) out.push_back(l);
  return out;
}

class CliRun : public ::testing::Test {
 protected:
  // One rendered scene for the whole suite: 3 frames of the built-in scene.
  static void SetUpTestSuite() {
    scene_dir_ = fs::temp_directory_path() / ("dv_cli_run_" + std::to_string(::getpid()));
    fs::remove_all(scene_dir_);
    SceneSpec spec = defaultScene();
    spec.frames = 3;
    writeScene(spec, scene_dir_.string());
  }
  static void TearDownTestSuite() { fs::remove_all(scene_dir_); }

  void SetUp() override {
    dir_ = scene_dir_ / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(dir_);
  }

  static std::string scene(const std::string& name) { return (scene_dir_ / name).string(); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  CliResult cli(const std::string& args) const {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string cmd = std::string("'") + DV_CLI_PATH + "' " + args + " >'" + out.string() +
                            "' 2>'" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    CliResult r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readAll(out);
    r.err = readAll(err);
    return r;
  }

  static inline fs::path scene_dir_;
  fs::path dir_;
};

// The built-in scene's camera is 1224 x 1024 with 11 mm of field per 2x2
// Bayer cell, so auto samples every pixel; the choice is logged
// once per camera and can be overridden.
TEST_F(CliRun, BayerSamplingIsChosenLoggedAndOverridable) {
  const std::string source = "run --source " + scene_dir_.string() + " --geometry " + scene("geometry.json") +
                             " --camera-id 0 --no-publish --max-frames 2";
  const CliResult a = cli(source);
  ASSERT_EQ(a.code, 0) << a.out << a.err;
  EXPECT_NE(a.out.find("camera 0: Bayer sampling full (auto: 2x2 cells cover"), std::string::npos) << a.out;
  EXPECT_EQ(a.out.find("Bayer sampling", a.out.find("Bayer sampling") + 1), std::string::npos) << "logged twice";
  const CliResult s = cli(source + " --bayer-sampling subsample");
  ASSERT_EQ(s.code, 0) << s.out << s.err;
  EXPECT_NE(s.out.find("Bayer sampling subsample (requested"), std::string::npos) << s.out;
  EXPECT_NE(s.out.find("2 processed, 0 skipped"), std::string::npos) << s.out;
  const CliResult bad = cli(source + " --bayer-sampling half");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--bayer-sampling 'half'"), std::string::npos) << bad.err;
}

// A full disk under the recording: one warning naming the file, every frame
// still detected (JSONL), and the summary and exit status (1) say so.
TEST_F(CliRun, FullDiskStopsRecordingButNotDetection) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const CliResult r = cli("run --source " + scene_dir_.string() + " --geometry " + scene("geometry.json") +
                          " --camera-id 0 --jsonl " + path("det.jsonl") + " --record /dev/full --no-publish");
  EXPECT_EQ(r.code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("3 processed, 0 skipped"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("recording stopped: /dev/full"), std::string::npos) << r.out;
  const size_t warning = r.err.find("warning: recording stopped: /dev/full");
  ASSERT_NE(warning, std::string::npos) << r.err;
  EXPECT_NE(r.err.find("No space left on device", warning), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("recording stopped", warning + 30), std::string::npos) << "warned twice: " << r.err;
  EXPECT_EQ(lines(readAll(path("det.jsonl"))).size(), 3u);
}

TEST_F(CliRun, ProcessesAnImageSequenceAndWritesJsonlAndLog) {
  // The directory `synth` wrote, as the README shows it.
  const CliResult r = cli("run --source " + scene_dir_.string() + " --geometry " + scene("geometry.json") +
                          " --camera-id 0 --jsonl " + path("det.jsonl") + " --record " + path("det.log") +
                          " --no-publish");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("3 processed, 0 skipped"), std::string::npos) << r.out;

  const auto jl = lines(readAll(path("det.jsonl")));
  ASSERT_EQ(jl.size(), 3u);
  // Unix time (the league's clients compute latency from it), anchored at
  // the run's start and spaced exactly as the frames are (index / fps).
  const double now = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  double t0 = 0;
  for (size_t i = 0; i < jl.size(); ++i) {
    ssl::SSL_WrapperPacket p;
    parseCanonicalJson(jl[i], p, "det.jsonl");
    ASSERT_TRUE(p.has_detection());
    EXPECT_EQ(p.detection().frame_number(), i);
    EXPECT_EQ(p.detection().camera_id(), 0u);
    if (i == 0) t0 = p.detection().t_capture();
    EXPECT_NEAR(p.detection().t_capture() - t0, i / 60.0, 1e-6);
    EXPECT_GE(p.detection().t_sent(), p.detection().t_capture() - i / 60.0);
    EXPECT_NEAR(p.detection().t_sent(), now, 120);
  }
  EXPECT_NEAR(t0, now, 120);
  const DetectionFile log = readDetectionFile(path("det.log"));
  EXPECT_EQ(log.frames.size(), 3u);
  EXPECT_TRUE(log.warnings.empty());

  // The recorded detections score against the scene's truth.
  const CliResult e = cli("eval --truth " + scene("truth.jsonl") + " --detections " + path("det.log") + " --json");
  ASSERT_EQ(e.code, 0) << e.err;
  const auto j = nlohmann::json::parse(e.out);
  EXPECT_EQ(j["overall"]["frames"].get<long>(), 3);
  EXPECT_EQ(j["overall"]["frames_missing"].get<long>(), 0);
  EXPECT_GT(j["overall"]["robots"]["truth"].get<long>(), 0);
  EXPECT_TRUE(j["per_camera"].contains("0"));

  // Several detection files are merged; the same frames twice are duplicates.
  const CliResult both = cli("eval --truth " + scene("truth.jsonl") + " --detections " + path("det.log") + " " +
                             path("det.jsonl") + " --json");
  ASSERT_EQ(both.code, 0) << both.err;
  const auto jb = nlohmann::json::parse(both.out);
  EXPECT_EQ(jb["detection_frames"].get<long>(), 6);
  EXPECT_EQ(jb["duplicate_detection_frames"].get<long>(), 3);
  EXPECT_EQ(jb["overall"]["robots"]["matched"], j["overall"]["robots"]["matched"]);
}

TEST_F(CliRun, PublishesGeometryAndDetectionsOnTheMulticastGroup) {
  const uint16_t port = static_cast<uint16_t>(20000 + (::getpid() % 20000));
  std::optional<MulticastReceiver> rx;
  try {
    rx.emplace("224.5.23.2", port, "127.0.0.1");
    MulticastSender probe("224.5.23.2", port, "127.0.0.1");
    probe.send(std::string("probe"));
    if (rx->receive(0.5) != std::optional<std::string>("probe"))
      GTEST_SKIP() << "loopback multicast does not deliver here";
  } catch (const InputError& e) {
    GTEST_SKIP() << "no loopback multicast: " << e.what();
  }
  const CliResult r = cli("run --source " + scene("frame_0_00000.pgm") + " --geometry " + scene("geometry.json") +
                          " --camera-id 0 --multicast-interface 127.0.0.1 --multicast-port " + std::to_string(port));
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("published 2 packets"), std::string::npos) << r.out;
  int geometry = 0, detection = 0;
  while (auto datagram = rx->receive(0.5)) {
    ssl::SSL_WrapperPacket p;
    ASSERT_TRUE(p.ParseFromString(*datagram));
    EXPECT_NE(p.has_geometry(), p.has_detection());  // separate datagrams, as ssl-vision sends them
    if (p.has_geometry()) ++geometry;
    if (p.has_detection()) {
      ++detection;
      EXPECT_EQ(p.detection().frame_number(), 0u);
      EXPECT_EQ(p.detection().camera_id(), 0u);
    }
  }
  EXPECT_EQ(geometry, 1);
  EXPECT_EQ(detection, 1);
}

TEST_F(CliRun, BadFramesAreSkippedNamedAndSummarised) {
  fs::create_directories(path("seq"));
  fs::copy_file(scene("frame_0_00000.pgm"), path("seq/a.pgm"));
  cv::imwrite(path("seq/b.png"), cv::Mat(100, 120, CV_8UC3, cv::Scalar(1, 2, 3)));  // wrong size
  fs::copy_file(scene("frame_0_00001.pgm"), path("seq/c.pgm"));
  fs::resize_file(path("seq/c.pgm"), fs::file_size(path("seq/c.pgm")) / 2);  // truncated
  std::ofstream(path("seq/d.jpg")) << "not a jpeg at all";
  fs::copy_file(scene("frame_0_00002.pgm"), path("seq/e.pgm"));
  const CliResult r = cli("run --source " + path("seq") + " --geometry " + scene("geometry.json") +
                          " --camera-id 0 --jsonl " + path("det.jsonl") + " --no-publish");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("2 processed, 3 skipped"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("b.png"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("120x100"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("c.pgm"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("d.jpg"), std::string::npos) << r.err;
  const auto jl = lines(readAll(path("det.jsonl")));
  ASSERT_EQ(jl.size(), 2u);
  ssl::SSL_WrapperPacket last;
  parseCanonicalJson(jl[1], last, "det.jsonl");
  EXPECT_EQ(last.detection().frame_number(), 4u);  // the source position, skipped ones counted
}

TEST_F(CliRun, MissingCameraIdInGeometryIsOneClearError) {
  const CliResult r = cli("run --source " + scene("frame_0_00000.pgm") + " --geometry " + scene("geometry.json") +
                          " --camera-id 7 --no-publish");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("geometry.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("camera id 7"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
}

TEST_F(CliRun, MalformedGeometryIsOneClearError) {
  std::ofstream(path("geometry.json")) << "{\"field\": {\"fieldLength\": 9000,";
  const CliResult r = cli("run --source " + scene("frame_0_00000.pgm") + " --geometry " + path("geometry.json") +
                          " --camera-id 0 --no-publish");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find(path("geometry.json")), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
}

TEST_F(CliRun, VideoSourceRunsToItsEnd) {
  cv::VideoWriter writer(path("clip.avi"), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 60,
                         cv::Size(1224, 1024));
  if (!writer.isOpened()) GTEST_SKIP() << "no FFmpeg video writer in this OpenCV build";
  for (int i = 0; i < 3; ++i) {
    cv::Mat raw = cv::imread(scene("frame_0_0000" + std::to_string(i) + ".pgm"), cv::IMREAD_UNCHANGED), bgr;
    cv::cvtColor(raw, bgr, cv::COLOR_BayerBG2BGR);  // RGGB sensor = OpenCV's "BG"
    writer.write(bgr);
  }
  writer.release();
  const CliResult r = cli("run --source " + path("clip.avi") + " --geometry " + scene("geometry.json") +
                          " --camera-id 0 --no-publish --jsonl " + path("det.jsonl"));
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("3 processed, 0 skipped"), std::string::npos) << r.out;
  const auto jl = lines(readAll(path("det.jsonl")));
  ASSERT_EQ(jl.size(), 3u);
  ssl::SSL_WrapperPacket p0, p;
  parseCanonicalJson(jl[0], p0, "det.jsonl");
  parseCanonicalJson(jl[2], p, "det.jsonl");
  EXPECT_NEAR(p.detection().t_capture() - p0.detection().t_capture(), 2 / 60.0, 1e-3);  // container time
}

TEST_F(CliRun, UnreadableVideoAndMissingSourceAreInputErrors) {
  std::ofstream(path("clip.mp4")) << "garbage";
  CliResult r = cli("run --source " + path("clip.mp4") + " --geometry " + scene("geometry.json") +
                    " --camera-id 0 --no-publish");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("clip.mp4"), std::string::npos) << r.err;
  r = cli("run --source " + path("nothing_here") + " --geometry " + scene("geometry.json") + " --no-publish");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("nothing_here"), std::string::npos) << r.err;
  r = cli("run --source " + scene("frame_0_00000.pgm") + " --no-publish");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--geometry"), std::string::npos) << r.err;
}

TEST_F(CliRun, UnknownOptionsAndBadValuesExitTwo) {
  CliResult r = cli("run --frobnicate");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("frobnicate"), std::string::npos) << r.err;
  r = cli("run --source " + scene("frame_0_00000.pgm") + " --geometry " + scene("geometry.json") +
          " --bayer rgbg --no-publish");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("rgbg"), std::string::npos) << r.err;
  r = cli("eval --truth " + scene("truth.jsonl"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--detections"), std::string::npos) << r.err;
  r = cli("bench --iterations 0");
  EXPECT_EQ(r.code, 2);
}

TEST_F(CliRun, EvalNamesTheBadLineAndWarnsAboutATruncatedLog) {
  std::ofstream(path("truth.jsonl")) << readAll(scene("truth.jsonl")) << "{\"frameNumber\": \n";
  CliResult r = cli("eval --truth " + path("truth.jsonl") + " --detections " + scene("truth.jsonl"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find(path("truth.jsonl") + ":4"), std::string::npos) << r.err;

  ASSERT_EQ(cli("run --source '" + scene("frame_0_*.pgm") + "' --geometry " + scene("geometry.json") +
                " --record " + path("det.log") + " --no-publish")
                .code,
            0);
  fs::resize_file(path("det.log"), fs::file_size(path("det.log")) - 5);
  r = cli("eval --truth " + scene("truth.jsonl") + " --detections " + path("det.log"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("det.log"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("overall: 3 frames (1 without detections)"), std::string::npos) << r.out;
}

TEST_F(CliRun, DebugViewsAreWritten) {
  const CliResult r = cli("run --source '" + scene("frame_0_*.pgm") + "' --geometry " + scene("geometry.json") +
                          " --no-publish --debug-dir " + path("dbg") + " --debug-frame 1");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* view : {"raw", "rectified", "gradient", "score", "detections"}) {
    const fs::path p = dir_ / "dbg" / (std::string("cam0_frame1_") + view + ".png");
    ASSERT_TRUE(fs::exists(p)) << p;
    EXPECT_FALSE(cv::imread(p.string(), cv::IMREAD_UNCHANGED).empty()) << p;
  }
  EXPECT_FALSE(fs::exists(dir_ / "dbg" / "cam0_frame0_raw.png"));
}

TEST_F(CliRun, SyntheticRunEndsWithTruthComparison) {
  const CliResult r = cli("run --no-publish --max-frames 2 --jsonl " + path("det.jsonl"));
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("synthetic scene"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 processed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("vs truth: robots recall"), std::string::npos) << r.out;
  EXPECT_EQ(lines(readAll(path("det.jsonl"))).size(), 2u);
}

// Two runs' detections of one frame agree: the same robots (team, id) and
// balls at the same places. Positions may differ in the last float digits
// (geometry.json stores the calibration as floats), so robots of nearly equal
// confidence may be listed in either order: they are matched by id.
void expectSameDetections(const ssl::SSL_DetectionFrame& a, const ssl::SSL_DetectionFrame& b) {
  EXPECT_EQ(a.frame_number(), b.frame_number());
  auto robots = [](const auto& x, const auto& y) {
    ASSERT_EQ(x.size(), y.size());
    for (const auto& r : x) {
      const auto same = std::find_if(y.begin(), y.end(),
                                     [&](const auto& q) { return q.robot_id() == r.robot_id(); });
      ASSERT_NE(same, y.end()) << "robot " << r.robot_id() << " missing in the second run";
      EXPECT_NEAR(r.x(), same->x(), 0.05);
      EXPECT_NEAR(r.y(), same->y(), 0.05);
      EXPECT_NEAR(r.orientation(), same->orientation(), 1e-4);
    }
  };
  robots(a.robots_yellow(), b.robots_yellow());
  robots(a.robots_blue(), b.robots_blue());
  ASSERT_EQ(a.balls_size(), b.balls_size());
  for (int i = 0; i < a.balls_size(); ++i) {
    EXPECT_NEAR(a.balls(i).x(), b.balls(i).x(), 0.05);
    EXPECT_NEAR(a.balls(i).y(), b.balls(i).y(), 0.05);
    EXPECT_NEAR(a.balls(i).confidence(), b.balls(i).confidence(), 1e-3);
  }
}

// A `synth` directory run with --fps 60 is tracked exactly as the same scene
// run from the renderer: same timestamps, same detections frame by frame.
// The motion preset at 1224x1024, a few frames: robots at up to 3 m/s
// turning at up to 4 rad/s, a 4 m/s ball, flicker and blur.
TEST_F(CliRun, ImageSequenceAt60FpsIsTrackedLikeTheSyntheticSource) {
  std::string yaml = readAll(fs::path(DV_SOURCE_DIR) / "config/scenes/motion_60fps_flicker.yaml");
  auto set = [&](const std::string& from, const std::string& to) {
    const size_t at = yaml.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    yaml.replace(at, from.size(), to);
  };
  set("focal_length: 1750", "focal_length: 875");
  set("size: [2448, 2048]", "size: [1224, 1024]");
  set("frames: 60", "frames: 6");
  set("motion_blur_samples: 7", "motion_blur_samples: 3");
  // A ball the pixel stage sees (a 6.5 m/s ball is a 52 mm streak that
  // scores below the blob threshold), so its track is compared too.
  set("ball_max_speed: 6500", "ball_max_speed: 4000");
  const std::string scene_file = path("motion.yaml");
  std::ofstream(scene_file) << yaml;

  const CliResult synth = cli("synth " + scene_file + " --out " + path("frames"));
  ASSERT_EQ(synth.code, 0) << synth.err;
  const CliResult seq = cli("run --source " + path("frames") + " --geometry " + path("frames/geometry.json") +
                            " --camera-id 0 --fps 60 --backend cpu --no-publish --jsonl " + path("seq.jsonl"));
  ASSERT_EQ(seq.code, 0) << seq.out << seq.err;
  const CliResult direct = cli("run --scene " + scene_file + " --backend cpu --no-publish --jsonl " +
                               path("direct.jsonl"));
  ASSERT_EQ(direct.code, 0) << direct.out << direct.err;

  const auto a = lines(readAll(path("seq.jsonl"))), b = lines(readAll(path("direct.jsonl")));
  ASSERT_EQ(a.size(), 6u);
  ASSERT_EQ(b.size(), 6u);
  double t0 = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    ssl::SSL_WrapperPacket pa, pb;
    parseCanonicalJson(a[i], pa, "seq.jsonl");
    parseCanonicalJson(b[i], pb, "direct.jsonl");
    if (i == 0) t0 = pa.detection().t_capture();
    EXPECT_NEAR(pa.detection().t_capture() - t0, i / 60.0, 1e-6);
    expectSameDetections(pa.detection(), pb.detection());
  }
  // And it is the scene: the robots and the ball found on these frames, with
  // no false robot (72 of 72 also with --no-guessed-ids, as a missing side
  // blob's color is read from the frame; 69 before).
  const CliResult e = cli("eval --truth " + path("frames/truth.jsonl") + " --detections " + path("seq.jsonl") +
                          " --json");
  ASSERT_EQ(e.code, 0) << e.err;
  const auto j = nlohmann::json::parse(e.out);
  EXPECT_GE(j["overall"]["robots"]["recall"].get<double>(), 0.98) << e.out;
  EXPECT_GE(j["overall"]["robots"]["precision"].get<double>(), 0.99) << e.out;
  EXPECT_GE(j["overall"]["balls"]["recall"].get<double>(), 0.98) << e.out;

  // Precision first: robots whose id would be a guess are left out.
  const CliResult strict = cli("run --source " + path("frames") + " --geometry " + path("frames/geometry.json") +
                               " --camera-id 0 --fps 60 --backend cpu --no-publish --no-guessed-ids --jsonl " +
                               path("strict.jsonl"));
  ASSERT_EQ(strict.code, 0) << strict.err;
  const CliResult es = cli("eval --truth " + path("frames/truth.jsonl") + " --detections " + path("strict.jsonl") +
                           " --json");
  ASSERT_EQ(es.code, 0) << es.err;
  const auto js = nlohmann::json::parse(es.out);
  EXPECT_LE(js["overall"]["robots"]["detected"].get<int>(), j["overall"]["robots"]["detected"].get<int>());
  EXPECT_GE(js["overall"]["robots"]["precision"].get<double>(), 0.99) << es.out;
  EXPECT_GE(js["overall"]["robots"]["recall"].get<double>(), 0.9) << es.out;
}

TEST_F(CliRun, BenchOnASourcePrintsJson) {
  const CliResult r = cli("bench --source " + scene("frame_0_00000.pgm") + " --geometry " + scene("geometry.json") +
                          " --iterations 3 --warmup 1 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["fps"].get<double>(), 0);
  EXPECT_GE(j["stages_ms"]["total"]["p99"].get<double>(), j["stages_ms"]["total"]["median"].get<double>());
  EXPECT_EQ(j["image_width"].get<int>(), 1224);
}

}  // namespace
}  // namespace dv

// Evaluation: pairing rules and every metric on hand-built truth/detections,
// plus the file readers' handling of malformed JSONL and truncated logs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/units.h"
#include "dotvision/ssl_wrapper.pb.h"
#include "eval/detection_files.h"
#include "eval/metrics.h"
#include "geometry/proto_json.h"
#include "io/ssl_log.h"

namespace dv {
namespace {

namespace fs = std::filesystem;
using ssl::SSL_DetectionFrame;

SSL_DetectionFrame frame(uint32_t camera, uint32_t number) {
  SSL_DetectionFrame f;
  f.set_camera_id(camera);
  f.set_frame_number(number);
  f.set_t_capture(number / 60.0);
  f.set_t_sent(number / 60.0);
  return f;
}

void robot(SSL_DetectionFrame& f, bool yellow, int id, double x, double y, double orientation = NAN) {
  auto* r = yellow ? f.add_robots_yellow() : f.add_robots_blue();
  r->set_robot_id(id);
  r->set_x(static_cast<float>(x));
  r->set_y(static_cast<float>(y));
  if (!std::isnan(orientation)) r->set_orientation(static_cast<float>(orientation));
  r->set_confidence(1);
  r->set_pixel_x(0);
  r->set_pixel_y(0);
}

void ball(SSL_DetectionFrame& f, double x, double y) {
  auto* b = f.add_balls();
  b->set_x(static_cast<float>(x));
  b->set_y(static_cast<float>(y));
  b->set_confidence(1);
  b->set_pixel_x(0);
  b->set_pixel_y(0);
}

// Camera 0, frame 0: two exact matches (yellow 1, blue 3), a wrong id
// (yellow 2 seen as 5), a wrong team (blue 4 seen as yellow 4), an extra
// robot, a matched ball and an extra ball. Camera 0, frame 1: no detection
// frame at all. Camera 1, frame 0: a robot seen 100 mm off (a miss).
struct Scenario {
  std::vector<SSL_DetectionFrame> truth, detections;
  Scenario() {
    SSL_DetectionFrame t0 = frame(0, 0), d0 = frame(0, 0);
    robot(t0, true, 1, 0, 0, 0.0);
    robot(d0, true, 1, 30, 40, 0.1);  // 50 mm off
    robot(t0, true, 2, 1000, 0);
    robot(d0, true, 5, 1010, 0);  // right team, wrong id
    robot(t0, false, 3, 2000, 0, 1.0);
    robot(d0, false, 3, 2000, 20, 1.2);  // 20 mm off
    robot(t0, false, 4, -1000, -1000);
    robot(d0, true, 4, -1000, -1000);  // wrong team: a false positive
    robot(d0, false, 7, 3000, 3000);   // nothing there
    ball(t0, 500, 500);
    ball(d0, 530, 540);  // exactly 50 mm off: still a match
    ball(d0, 4000, 0);   // extra
    SSL_DetectionFrame t1 = frame(0, 1);
    ball(t1, 0, 0);
    SSL_DetectionFrame t2 = frame(1, 0), d2 = frame(1, 0);
    robot(t2, true, 0, 0, 0);
    robot(d2, true, 0, 100, 0);
    truth = {t0, t1, t2};
    detections = {d0, d2};
  }
};

TEST(EvalMetrics, PercentileAndMedian) {
  EXPECT_DOUBLE_EQ(percentile({}, 0.95), 0);
  EXPECT_DOUBLE_EQ(percentile({3, 1, 2}, 0.5), 2);
  std::vector<double> hundred;
  for (int i = 1; i <= 100; ++i) hundred.push_back(i);
  EXPECT_DOUBLE_EQ(percentile(hundred, 0.95), 95);
  const ErrorStats s = errorStats({4, 1, 3, 2});
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.p95, 4);
  EXPECT_EQ(s.count, 4);
}

TEST(EvalMetrics, CountsEveryKindOfMatchAndMistake) {
  const Scenario sc;
  const EvalReport r = evaluate(sc.truth, sc.detections);
  ASSERT_EQ(r.per_camera.size(), 2u);
  const Metrics& c0 = r.per_camera.at(0);
  EXPECT_EQ(c0.frames, 2);
  EXPECT_EQ(c0.frames_missing, 1);
  EXPECT_EQ(c0.truth_robots, 4);
  EXPECT_EQ(c0.detected_robots, 5);
  EXPECT_EQ(c0.matched_robots, 2);
  EXPECT_DOUBLE_EQ(c0.robotRecall(), 0.5);
  EXPECT_DOUBLE_EQ(c0.robotPrecision(), 0.4);
  EXPECT_EQ(c0.team_matched_robots, 3);
  EXPECT_DOUBLE_EQ(c0.teamRecall(), 0.75);
  EXPECT_DOUBLE_EQ(c0.idAccuracy(), 2.0 / 3.0);
  EXPECT_EQ(c0.false_positive_robots, 2);
  EXPECT_EQ(c0.truth_balls, 2);
  EXPECT_EQ(c0.detected_balls, 2);
  EXPECT_EQ(c0.matched_balls, 1);
  EXPECT_DOUBLE_EQ(c0.ballRecall(), 0.5);
  EXPECT_DOUBLE_EQ(c0.ballPrecision(), 0.5);
  EXPECT_EQ(c0.false_positive_balls, 1);
  EXPECT_DOUBLE_EQ(c0.falsePositivesPerFrame(), 1.5);

  const ErrorStats pos = errorStats(c0.robot_position_errors_mm);
  EXPECT_NEAR(pos.median, 35, 1e-3);
  EXPECT_NEAR(pos.p95, 50, 1e-3);
  const ErrorStats ori = errorStats(c0.robot_orientation_errors_rad);
  EXPECT_NEAR(ori.median, 0.15, 1e-6);
  EXPECT_NEAR(ori.p95, 0.2, 1e-6);
  const ErrorStats bp = errorStats(c0.ball_position_errors_mm);
  EXPECT_NEAR(bp.median, 50, 1e-3);

  const Metrics& c1 = r.per_camera.at(1);
  EXPECT_EQ(c1.matched_robots, 0);
  EXPECT_EQ(c1.team_matched_robots, 0);  // 100 mm is beyond the 60 mm radius
  EXPECT_EQ(c1.false_positive_robots, 1);

  EXPECT_EQ(r.overall.frames, 3);
  EXPECT_EQ(r.overall.truth_robots, 5);
  EXPECT_EQ(r.overall.detected_robots, 6);
  EXPECT_DOUBLE_EQ(r.overall.robotRecall(), 0.4);
  EXPECT_DOUBLE_EQ(r.overall.robotPrecision(), 2.0 / 6.0);
  EXPECT_DOUBLE_EQ(r.overall.falsePositivesPerFrame(), 4.0 / 3.0);
}

TEST(EvalMetrics, RadiusIsConfigurable) {
  const Scenario sc;
  MatchOptions wide;
  wide.robot_radius_mm = 150;
  EXPECT_EQ(evaluate(sc.truth, sc.detections, wide).per_camera.at(1).matched_robots, 1);
}

TEST(EvalMetrics, OrientationErrorWrapsAroundPi) {
  SSL_DetectionFrame t = frame(0, 0), d = frame(0, 0);
  robot(t, false, 9, 0, 0, 3.1);
  robot(d, false, 9, 0, 0, -3.1);
  const EvalReport r = evaluate({t}, {d});
  ASSERT_EQ(r.overall.robot_orientation_errors_rad.size(), 1u);
  EXPECT_NEAR(r.overall.robot_orientation_errors_rad[0], 2 * kPi - 6.2, 1e-5);
}

TEST(EvalMetrics, ClosestPairWinsWhenTwoDetectionsCompete) {
  SSL_DetectionFrame t = frame(0, 0), d = frame(0, 0);
  ball(t, 0, 0);
  ball(t, 60, 0);
  ball(d, 40, 0);  // closer to the second truth ball (20 mm) than to the first (40 mm)
  const EvalReport r = evaluate({t}, {d});
  EXPECT_EQ(r.overall.matched_balls, 1);
  EXPECT_NEAR(r.overall.ball_position_errors_mm[0], 20, 1e-4);
}

TEST(EvalMetrics, DetectionFramesWithoutTruthAndDuplicatesAreCounted) {
  const Scenario sc;
  auto dets = sc.detections;
  dets.push_back(frame(5, 0));
  dets.push_back(sc.detections[0]);
  const EvalReport r = evaluate(sc.truth, dets);
  EXPECT_EQ(r.detection_frames_unmatched, 1);
  EXPECT_EQ(r.duplicate_detection_frames, 1);
  const auto j = nlohmann::json::parse(reportJson(r));
  EXPECT_DOUBLE_EQ(j["per_camera"]["0"]["robots"]["recall"].get<double>(), 0.5);
  EXPECT_EQ(j["overall"]["frames"].get<long>(), 3);
  EXPECT_NE(formatReport(r).find("camera 1"), std::string::npos);
}

// ---- files ----

class EvalFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("dv_eval_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void writeText(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
  }
  fs::path dir_;
};

TEST_F(EvalFiles, JsonlRoundTripGivesTheSameMetrics) {
  const Scenario sc;
  std::string truth, det;
  for (const auto& f : sc.truth) truth += toCanonicalJson(f) + "\n";
  for (const auto& f : sc.detections) {
    ssl::SSL_WrapperPacket w;
    *w.mutable_detection() = f;
    det += toCanonicalJson(w) + "\n\n";  // blank lines are allowed
  }
  writeText("truth.jsonl", truth);
  writeText("det.jsonl", det);
  const auto t = readTruthJsonl(path("truth.jsonl"));
  const auto d = readDetectionFile(path("det.jsonl"));
  ASSERT_EQ(t.frames.size(), 3u);
  ASSERT_EQ(d.frames.size(), 2u);
  EXPECT_TRUE(d.warnings.empty());
  EXPECT_EQ(evaluate(t.frames, d.frames).overall.matched_robots, 2);
}

TEST_F(EvalFiles, MalformedJsonlLineNamesFileAndLine) {
  const Scenario sc;
  writeText("truth.jsonl", toCanonicalJson(sc.truth[0]) + "\n{\"frameNumber\": 1, oops\n");
  try {
    readTruthJsonl(path("truth.jsonl"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path("truth.jsonl") + ":2"), std::string::npos) << e.what();
  }
  // A JSON object that lacks required fields is malformed too.
  writeText("det.jsonl", "{\"detection\": {\"frameNumber\": 3}}\n");
  try {
    readDetectionFile(path("det.jsonl"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("det.jsonl:1"), std::string::npos) << e.what();
  }
}

TEST_F(EvalFiles, MissingFileIsAnInputError) {
  EXPECT_THROW(readTruthJsonl(path("nope.jsonl")), InputError);
  EXPECT_THROW(readDetectionFile(path("nope.log")), InputError);
}

TEST_F(EvalFiles, ReadsSslLogAndKeepsRecordsBeforeATruncation) {
  const Scenario sc;
  {
    SslLogWriter w(path("det.log"));
    for (const auto& f : sc.detections) {
      ssl::SSL_WrapperPacket p;
      *p.mutable_detection() = f;
      w.write(1000, LogMessageType::Vision2014, p.SerializeAsString());
    }
    w.write(2000, LogMessageType::Refbox2013, "not vision");  // ignored type
    ssl::SSL_WrapperPacket last;
    *last.mutable_detection() = frame(0, 1);
    w.write(3000, LogMessageType::Vision2014, last.SerializeAsString());
  }
  const auto full = readDetectionFile(path("det.log"));
  EXPECT_EQ(full.frames.size(), 3u);
  EXPECT_TRUE(full.warnings.empty());

  fs::resize_file(path("det.log"), fs::file_size(path("det.log")) - 3);
  const auto cut = readDetectionFile(path("det.log"));
  EXPECT_EQ(cut.frames.size(), 2u);
  ASSERT_EQ(cut.warnings.size(), 1u);
  EXPECT_NE(cut.warnings[0].find(path("det.log")), std::string::npos) << cut.warnings[0];
}

TEST_F(EvalFiles, GarbageLogRecordIsAnInputErrorWithOffset) {
  {
    SslLogWriter w(path("bad.log"));
    w.write(1, LogMessageType::Vision2014, std::string("\xff\xff\xff\x0f", 4));
  }
  try {
    readDetectionFile(path("bad.log"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("byte 16"), std::string::npos) << e.what();
  }
}

// A packet missing required fields (found fuzzing): named in the error, and
// protobuf prints no line of its own before it.
TEST_F(EvalFiles, LogPacketMissingRequiredFieldsIsNamedQuietly) {
  {
    SslLogWriter w(path("partial.log"));
    ssl::SSL_WrapperPacket p;
    *p.mutable_detection() = frame(0, 1);
    p.mutable_detection()->add_robots_yellow()->set_confidence(1);
    w.write(1, LogMessageType::Vision2014, p.SerializePartialAsString());
  }
  ::testing::internal::CaptureStderr();
  try {
    readDetectionFile(path("partial.log"));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path("partial.log")), std::string::npos) << what;
    EXPECT_NE(what.find("byte 16"), std::string::npos) << what;
    EXPECT_NE(what.find("lacks required fields"), std::string::npos) << what;
    EXPECT_NE(what.find("robots_yellow[0].x"), std::string::npos) << what;
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST_F(EvalFiles, DamagedLogHeaderIsReportedAsSuch) {
  {
    SslLogWriter w(path("damaged.log"));
    ssl::SSL_WrapperPacket p;
    *p.mutable_detection() = frame(0, 1);
    w.write(1000, LogMessageType::Vision2014, p.SerializeAsString());
  }
  {
    std::fstream f(path("damaged.log"), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(11);
    f.put('X');  // SSL_LOG_FILX
  }
  try {
    readDetectionFile(path("damaged.log"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path("damaged.log")), std::string::npos) << what;
    EXPECT_NE(what.find("damaged SSL log header"), std::string::npos) << what;
    EXPECT_EQ(what.find("JSON"), std::string::npos) << what;
  }
}

TEST_F(EvalFiles, FileWithoutDetectionFramesWarns) {
  writeText("empty.jsonl", "");
  const auto d = readDetectionFile(path("empty.jsonl"));
  EXPECT_TRUE(d.frames.empty());
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find(path("empty.jsonl") + ": holds no detection frames"), std::string::npos)
      << d.warnings[0];
}

}  // namespace
}  // namespace dv

// A processor on a live GigE Vision stream: the built-in scene's rendered
// Bayer frames sent by Aravis's fake camera over loopback are detected
// exactly as the same frames read from files, and a processor slower than
// the camera takes the newest frame with the older ones counted as drops.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "app/camera_processor.h"
#include "app/synthetic_source.h"
#include "camera/genicam_source.h"
#include "fake_gige_camera.h"
#include "live/live_camera.h"
#include "synth/scene.h"

namespace dv {
namespace {

using test::FakeGigeCamera;

struct Rendered {
  SceneSpec spec;
  std::vector<cv::Mat> frames;
  std::vector<std::vector<uint8_t>> bytes;
};

Rendered renderDefault() {
  Rendered r;
  r.spec = defaultScene();  // one 1224 x 1024 RGGB camera, 12 robots and the ball
  r.spec.frames = 3;
  app::SyntheticSource source(r.spec, {});
  Frame f;
  while (source.next(f)) {
    r.frames.push_back(f.image.clone());
    r.bytes.emplace_back(f.image.datastart, f.image.dataend);
  }
  return r;
}

app::ProcessorOptions singleFrameOptions() {
  app::ProcessorOptions o;
  o.backend.backend = Backend::Cpu;
  o.detector.tracking = false;  // each frame alone: time stamps do not enter
  o.pipeline.bayer = BayerPattern::RGGB;
  return o;
}

std::string uniqueSerial(const char* tag) { return std::string("DV") + tag + std::to_string(::getpid() % 100000); }
const std::vector<CameraSetting> kSceneFormat = {{"PixelFormat", "BayerRG8"}, {"Width", "1224"}, {"Height", "1024"}};

TEST(GenicamLive, DetectionsOverGigeEqualThoseOfTheSameFramesFromFiles) {
  const Rendered scene = renderDefault();
  FakeGigeCamera cam(uniqueSerial("det"), 1224, 1024);
  if (!cam.running()) GTEST_SKIP() << "Aravis's fake GigE camera cannot listen on 127.0.0.1:3956";
  cam.streamImages(scene.bytes);
  GenicamSource src(cam.deviceId());
  src.applySettings(kSceneFormat);
  app::CameraProcessor live(scene.spec.cameras[0].calib, scene.spec.field, singleFrameOptions());
  app::CameraProcessor files(scene.spec.cameras[0].calib, scene.spec.field, singleFrameOptions());
  Frame f;
  std::string why;
  int compared = 0;
  for (int tries = 0; tries < 200 && compared < 6; ++tries) {
    if (src.grab(f, 2.0, why) != GrabStatus::Frame) continue;
    ASSERT_EQ(f.format, PixelFormat::BayerRggb8);
    // Which rendered frame this is: the bytes are the same, or it is not one of them.
    int k = -1;
    for (size_t i = 0; i < scene.frames.size(); ++i)
      if (f.image.size() == scene.frames[i].size() && cv::norm(f.image, scene.frames[i], cv::NORM_INF) == 0)
        k = static_cast<int>(i);
    ASSERT_GE(k, 0) << "a frame over GigE differs from every rendered frame";
    Frame from_file;
    from_file.image = scene.frames[k];
    from_file.format = PixelFormat::BayerRggb8;
    from_file.t_capture = f.t_capture;
    Detections a, b;
    ASSERT_TRUE(live.process(f, a, why)) << why;
    ASSERT_TRUE(files.process(from_file, b, why)) << why;
    ASSERT_GE(a.robots.size(), 10u);
    ASSERT_EQ(a.robots.size(), b.robots.size());
    ASSERT_EQ(a.balls.size(), b.balls.size());
    for (size_t i = 0; i < a.robots.size(); ++i) {
      EXPECT_EQ(a.robots[i].id, b.robots[i].id);
      EXPECT_EQ(a.robots[i].position.x, b.robots[i].position.x);  // to the bit
      EXPECT_EQ(a.robots[i].position.y, b.robots[i].position.y);
      EXPECT_EQ(a.robots[i].orientation, b.robots[i].orientation);
    }
    ++compared;
  }
  EXPECT_EQ(compared, 6);
}

TEST(GenicamLive, AProcessorSlowerThanTheCameraDropsOldFramesAndStaysCurrent) {
  FakeGigeCamera cam(uniqueSerial("slow"), 640, 480);
  if (!cam.running()) GTEST_SKIP() << "Aravis's fake GigE camera cannot listen on 127.0.0.1:3956";
  auto src = std::make_unique<GenicamSource>(cam.deviceId());
  src->applySettings({{"Width", "640"}, {"Height", "480"}, {"AcquisitionFrameRate", "60"}});
  std::vector<double> waits;
  std::mutex m;
  LiveCamera live("camera 0", std::move(src),
                  [&](Frame& f, double t_taken) {
                    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // 20 fps against 60
                    std::lock_guard<std::mutex> lock(m);
                    waits.push_back(t_taken - f.t_arrival);
                  },
                  nullptr);
  live.start();
  std::this_thread::sleep_for(std::chrono::seconds(4));
  live.stop();
  const LiveCounters c = live.counters();
  EXPECT_GT(c.frames_in, 60u);
  EXPECT_GT(c.dropped, c.frames_in / 3);  // most frames replaced unseen
  EXPECT_EQ(c.processed + c.dropped, c.frames_in);
  std::lock_guard<std::mutex> lock(m);
  ASSERT_GT(waits.size(), 20u);
  std::sort(waits.begin(), waits.end());
  EXPECT_LT(waits[waits.size() * 99 / 100], 0.2);  // a frame never waits behind a queue
}

// Packets lost on the link mid-stream: a buffer that comes incomplete is
// skipped with its reason and counted, the whole ones are the camera's bytes
// and are processed, and the stream never stops.
TEST(GenicamLive, IncompleteBuffersMidStreamAreSkippedCountedAndTheStreamGoesOn) {
  FakeGigeCamera cam(uniqueSerial("lossy"), 640, 480);
  if (!cam.running()) GTEST_SKIP() << "Aravis's fake GigE camera cannot listen on 127.0.0.1:3956";
  GenicamSource src(cam.deviceId());
  src.applySettings({{"Width", "640"}, {"Height", "480"}, {"AcquisitionFrameRate", "30"}});
  Frame f;
  std::string why;
  int whole_before = 0;
  for (int i = 0; i < 100 && whole_before < 5; ++i)
    if (src.grab(f, 2.0, why) == GrabStatus::Frame) ++whole_before;
  ASSERT_EQ(whole_before, 5) << why;
  cam.losePackets(3);  // 0.3 % of 220 packets a frame: about half the frames lose one
  int whole = 0, skipped = 0;
  std::string skip_reason;
  for (int i = 0; i < 200 && (whole < 5 || skipped < 5); ++i) {
    const GrabStatus s = src.grab(f, 2.0, why);
    if (s == GrabStatus::Frame) {
      ++whole;
      EXPECT_EQ(f.image.cols, 640);
      std::vector<uint8_t> want(640 * 480);
      test::fakePattern(want.data(), want.size(), test::fakePatternSeq(f.image.data));
      EXPECT_EQ(std::memcmp(want.data(), f.image.data, want.size()), 0) << "a frame taken is whole";
    } else if (s == GrabStatus::Skipped) {
      ++skipped;
      skip_reason = why;
    }
  }
  EXPECT_GE(skipped, 5);
  EXPECT_GE(whole, 5);
  EXPECT_NE(skip_reason.find(cam.deviceId()), std::string::npos) << skip_reason;
  EXPECT_NE(skip_reason.find("frame "), std::string::npos) << skip_reason;
  EXPECT_GE(src.counters().skipped, static_cast<uint64_t>(skipped));
  cam.losePackets(0);
  int after = 0;
  for (int i = 0; i < 100 && after < 5; ++i)
    if (src.grab(f, 2.0, why) == GrabStatus::Frame) ++after;
  EXPECT_EQ(after, 5) << "the stream goes on once the link is clean";
}

}  // namespace
}  // namespace dv

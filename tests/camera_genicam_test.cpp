// GenicamSource over Aravis's fake GigE Vision camera on loopback: the real
// protocols (GVCP discovery and control, GVSP stream), no mocks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <future>
#include <thread>
#include <vector>

#include "camera/camera_list.h"
#include "camera/genicam_source.h"
#include "camera/gvcp_probe.h"
#include "camera/open_camera.h"
#include "core/error.h"
#include "fake_gige_camera.h"
#include "temp_dir.h"

namespace dv {
namespace {

using test::FakeGigeCamera;

// A serial of its own per test (GigE serials are at most 16 characters).
std::string uniqueSerial(const char* tag) { return std::string("DV") + tag + std::to_string(::getpid() % 100000); }

#define REQUIRE_FAKE(cam)                                                                         \
  if (!(cam).running())                                                                           \
  GTEST_SKIP() << "Aravis's fake GigE camera cannot listen on 127.0.0.1:3956 (no loopback "     \
                  "interface, or another GigE Vision program holds the port)"

const std::vector<CameraSetting> kSmall = {{"Width", "640"}, {"Height", "480"}};

// Grabs until `n` frames came (skips allowed), within a generous limit.
std::vector<Frame> grabFrames(CameraSource& src, int n, double limit_s = 30) {
  std::vector<Frame> out;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  Frame f;
  std::string why;
  while (static_cast<int>(out.size()) < n && std::chrono::steady_clock::now() < end) {
    const GrabStatus s = src.grab(f, 1.0, why);
    if (s == GrabStatus::Frame) {
      Frame copy = f;
      copy.image = f.image.clone();
      out.push_back(std::move(copy));
    } else if (s == GrabStatus::Lost) {
      ADD_FAILURE() << "camera lost: " << why;
      break;
    }
  }
  return out;
}

std::string errorOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(GenicamCameraTest, FramesOverGigeAreTheBytesTheCameraWrote) {
  FakeGigeCamera cam(uniqueSerial("bits"));
  REQUIRE_FAKE(cam);
  GenicamSource src(cam.serial());  // by serial number
  EXPECT_EQ(src.deviceId(), cam.deviceId());
  auto settings = kSmall;
  settings.push_back({"PixelFormat", "BayerGR8"});
  src.applySettings(settings);
  const auto frames = grabFrames(src, 20);
  ASSERT_EQ(frames.size(), 20u);
  std::vector<uint8_t> expected(640 * 480);
  uint32_t previous_seq = 0;
  for (const Frame& f : frames) {
    ASSERT_EQ(f.format, PixelFormat::BayerGrbg8);  // the layout the camera reports
    ASSERT_EQ(f.image.type(), CV_8UC1);
    ASSERT_EQ(f.image.cols, 640);
    ASSERT_EQ(f.image.rows, 480);
    ASSERT_TRUE(f.image.isContinuous());
    const uint32_t seq = test::fakePatternSeq(f.image.ptr<uint8_t>());
    EXPECT_GT(seq, previous_seq) << "frames out of order";
    previous_seq = seq;
    test::fakePattern(expected.data(), expected.size(), seq);
    EXPECT_EQ(0, std::memcmp(expected.data(), f.image.ptr<uint8_t>(), expected.size())) << "frame " << f.name;
    EXPECT_EQ(f.name.rfind("genicam://" + cam.serial() + "#", 0), 0u) << f.name;
  }
  const SourceCounters c = src.counters();
  EXPECT_GE(c.frames, 20u);
  EXPECT_NE(src.describe().find("BayerGR8 640x480"), std::string::npos) << src.describe();
}

TEST(GenicamCameraTest, Rgb8BecomesBgr) {
  FakeGigeCamera cam(uniqueSerial("rgb"));
  REQUIRE_FAKE(cam);
  GenicamSource src(cam.deviceId());
  src.applySettings({{"Width", "320"}, {"Height", "240"}, {"PixelFormat", "RGB8"}});
  const auto frames = grabFrames(src, 5);
  ASSERT_EQ(frames.size(), 5u);
  std::vector<uint8_t> rgb(320 * 240 * 3);
  for (const Frame& f : frames) {
    ASSERT_EQ(f.format, PixelFormat::Bgr8);
    ASSERT_EQ(f.image.type(), CV_8UC3);
    const uint8_t* bgr = f.image.ptr<uint8_t>();
    const uint8_t first[4] = {bgr[2], bgr[1], bgr[0], bgr[5]};  // back to the camera's RGB order
    test::fakePattern(rgb.data(), rgb.size(), test::fakePatternSeq(first));
    for (size_t i = 0; i < rgb.size(); i += 3)
      ASSERT_TRUE(bgr[i] == rgb[i + 2] && bgr[i + 1] == rgb[i + 1] && bgr[i + 2] == rgb[i]) << "pixel " << i / 3;
  }
}

TEST(GenicamCameraTest, TwelveBitPackedBayerIsReducedToItsHighEightBits) {
  TempDir dir("dv_genicam_xml");
  const std::string xml = dir.file("fake_12bit.xml");
  ASSERT_TRUE(test::writeFakeGenicamWithFormats(xml, {{"BayerRG12Packed", 0x010c002b}}));
  FakeGigeCamera cam(uniqueSerial("p12"), 2448, 2048, false, xml);
  REQUIRE_FAKE(cam);
  GenicamSource src(cam.deviceId());
  src.applySettings({{"Width", "640"}, {"Height", "480"}, {"PixelFormat", "BayerRG12Packed"}});
  const auto frames = grabFrames(src, 5);
  ASSERT_EQ(frames.size(), 5u);
  const size_t pixels = 640 * 480;
  std::vector<uint8_t> raw(pixels * 3 / 2);
  for (const Frame& f : frames) {
    ASSERT_EQ(f.format, PixelFormat::BayerRggb8);
    ASSERT_EQ(f.image.type(), CV_8UC1);
    // Of the seq in raw bytes 0..3, bytes 0, 2, 3 survive the reduction
    // (pixels 0, 1, 2 are raw bytes 0, 2, 3): find the one byte missing.
    const uint8_t* out = f.image.ptr<uint8_t>();
    uint32_t seq = 0;
    bool found = false;
    for (uint32_t k = 0; k < 256 && !found; ++k) {
      seq = out[0] | k << 8 | uint32_t(out[1]) << 16 | uint32_t(out[2]) << 24;
      uint8_t prefix[48];
      test::fakePattern(prefix, sizeof prefix, seq);
      found = true;
      for (size_t i = 0; i < 32 && found; ++i) found = out[i] == prefix[(i / 2) * 3 + (i % 2) * 2];
    }
    ASSERT_TRUE(found) << "no camera frame matches " << f.name;
    test::fakePattern(raw.data(), raw.size(), seq);
    for (size_t i = 0; i < pixels; ++i)  // GigE packing: the high 8 bits are bytes 0 and 2 of each triple
      ASSERT_EQ(out[i], raw[(i / 2) * 3 + (i % 2) * 2]) << "pixel " << i << " of " << f.name;
  }
}

TEST(GenicamCameraTest, MonoDefaultIsReplacedByBayerAndTheOnlyCameraIsFoundWithoutId) {
  FakeGigeCamera cam(uniqueSerial("only"));  // the fake starts in Mono8
  REQUIRE_FAKE(cam);
  GenicamSource src("");
  EXPECT_EQ(src.deviceId(), cam.deviceId());
  src.applySettings(kSmall);
  const auto frames = grabFrames(src, 2);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_NE(frames[0].format, PixelFormat::Bgr8);
  EXPECT_NE(src.describe().find("Bayer"), std::string::npos) << src.describe();
}

TEST(GenicamCameraTest, SettingsAreAppliedInOrderAndReadBack) {
  FakeGigeCamera cam(uniqueSerial("set"));
  REQUIRE_FAKE(cam);
  auto src = openCameraSource("genicam://" + cam.deviceId(), {});
  const auto lines = src->applySettings(
      {{"ExposureTimeAbs", "4000"}, {"GainRaw", "3"}, {"GainAuto", "Off"}, {"Width", "800"}, {"Width", "640"}});
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0].rfind("ExposureTimeAbs = 4000", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1], "GainRaw = 3");
  EXPECT_EQ(lines[2], "GainAuto = Off");
  EXPECT_EQ(lines[4], "Width = 640");
  const auto frames = grabFrames(*src, 1);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].image.cols, 640);  // the last Width given wins
}

TEST(GenicamCameraTest, StartupDefaultsAreContinuousNoAutoGainAndAtMost75Fps) {
  FakeGigeCamera cam(uniqueSerial("def"));
  REQUIRE_FAKE(cam);
  cam.setReg(ARV_FAKE_CAMERA_REGISTER_GAIN_MODE, 2);                   // GainAuto = Continuous
  cam.setReg(ARV_FAKE_CAMERA_REGISTER_ACQUISITION_MODE, 2);            // SingleFrame
  cam.setReg(ARV_FAKE_CAMERA_REGISTER_ACQUISITION_FRAME_PERIOD_US, 100000);  // 10 fps
  GenicamSource src(cam.deviceId());
  EXPECT_EQ(cam.reg(ARV_FAKE_CAMERA_REGISTER_GAIN_MODE), 1u) << "GainAuto Off";
  EXPECT_EQ(cam.reg(ARV_FAKE_CAMERA_REGISTER_ACQUISITION_MODE), 1u) << "Continuous";
  // The fake allows up to 1000 fps; the default is capped at 75 (period 13333 us).
  EXPECT_NEAR(cam.reg(ARV_FAKE_CAMERA_REGISTER_ACQUISITION_FRAME_PERIOD_US), 13333.0, 1.0);
  // A setting overrides a default.
  src.applySettings({{"AcquisitionFrameRate", "20"}});
  EXPECT_EQ(cam.reg(ARV_FAKE_CAMERA_REGISTER_ACQUISITION_FRAME_PERIOD_US), 50000u);
}

TEST(GenicamCameraTest, UnknownFeatureAndRefusedValuesAreClearErrors) {
  FakeGigeCamera cam(uniqueSerial("bad"));
  REQUIRE_FAKE(cam);
  GenicamSource src(cam.deviceId());
  const std::string spec = "genicam://" + cam.deviceId();
  auto apply = [&](const char* name, const char* value) {
    return errorOf([&] { src.applySettings({{name, value}}); });
  };
  const std::string unknown = apply("NoSuchFeature", "1");
  EXPECT_NE(unknown.find(spec), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("no feature 'NoSuchFeature'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("Aravis Fake, serial " + cam.serial()), std::string::npos) << unknown;
  // The SFNC name on a camera that has the older one: a suggestion.
  EXPECT_NE(apply("ExposureTime", "4000").find("did you mean ExposureTimeAbs?"), std::string::npos);
  EXPECT_NE(apply("GainRaw", "99").find("out of range 0 .. 10"), std::string::npos) << apply("GainRaw", "99");
  EXPECT_NE(apply("ExposureTimeAbs", "fast").find("'fast' is not a number"), std::string::npos);
  const std::string format = apply("PixelFormat", "Purple");
  EXPECT_NE(format.find("PixelFormat=Purple"), std::string::npos) << format;
  EXPECT_NE(format.find("BayerRG8"), std::string::npos) << "lists what the camera offers: " << format;
  EXPECT_NE(apply("SensorWidth", "100").find("read-only"), std::string::npos) << apply("SensorWidth", "100");
  EXPECT_NE(apply("TestBoolean", "maybe").find("not a boolean"), std::string::npos);
}

TEST(GenicamCameraTest, Mono8IsRefused) {
  FakeGigeCamera cam(uniqueSerial("mono"));
  REQUIRE_FAKE(cam);
  GenicamSource src(cam.deviceId());
  const std::string e = errorOf([&] { src.applySettings({{"PixelFormat", "Mono8"}}); });
  EXPECT_NE(e.find("PixelFormat=Mono8"), std::string::npos) << e;
  EXPECT_NE(e.find("monochrome"), std::string::npos) << e;
  EXPECT_NE(e.find("genicam://"), std::string::npos) << e;
}

TEST(GenicamCameraTest, AbsentIdIsRefusedListingTheCamerasPresent) {
  FakeGigeCamera cam(uniqueSerial("abs"));
  REQUIRE_FAKE(cam);
  const std::string e = errorOf([] { openCameraSource("genicam://NoSuchCamera", {}); });
  EXPECT_NE(e.find("genicam://NoSuchCamera"), std::string::npos) << e;
  EXPECT_NE(e.find("no GenICam camera 'NoSuchCamera'"), std::string::npos) << e;
  EXPECT_NE(e.find(cam.deviceId() + " (serial " + cam.serial() + ", GigE 127.0.0.1)"), std::string::npos) << e;
}

TEST(GenicamCameraTest, CameraListShowsTheFakeCamera) {
  FakeGigeCamera cam(uniqueSerial("list"));
  REQUIRE_FAKE(cam);
  const auto cams = listGenicamCameras(true);
  const auto it = std::find_if(cams.begin(), cams.end(), [&](const auto& c) { return c.id == cam.deviceId(); });
  ASSERT_NE(it, cams.end());
  EXPECT_EQ(it->vendor, "Aravis");
  EXPECT_EQ(it->model, "Fake");
  EXPECT_EQ(it->serial, cam.serial());
  EXPECT_EQ(it->interfaceText(), "GigE 127.0.0.1");
  EXPECT_EQ(it->pixel_format, "Mono8");
  EXPECT_EQ(it->width, 512);
  EXPECT_EQ(it->height, 512);
  EXPECT_TRUE(it->problem.empty()) << it->problem;

  // And the same through the CLI.
  FILE* p = popen((std::string("'") + DV_CLI_PATH + "' cameras 2>&1").c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[512];
  while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  EXPECT_EQ(pclose(p), 0) << out;
  EXPECT_NE(out.find("genicam://" + cam.deviceId()), std::string::npos) << out;
  EXPECT_NE(out.find("Aravis Fake, serial " + cam.serial() + ", GigE 127.0.0.1"), std::string::npos) << out;
  EXPECT_NE(out.find("Mono8 512x512"), std::string::npos) << out;
}

TEST(GenicamCameraTest, CaptureTimesIncreaseAndStayJustBeforeArrival) {
  FakeGigeCamera cam(uniqueSerial("time"));
  REQUIRE_FAKE(cam);
  GenicamSource src(cam.deviceId());
  src.applySettings({{"Width", "320"}, {"Height", "240"}});
  const auto frames = grabFrames(src, 60);
  ASSERT_EQ(frames.size(), 60u);
  std::vector<double> behind;
  for (size_t i = 0; i < frames.size(); ++i) {
    const Frame& f = frames[i];
    ASSERT_GT(f.t_capture_camera, 0) << "the fake camera stamps its frames";
    EXPECT_LE(f.t_capture, f.t_arrival) << "frame " << i;
    if (i) {
      EXPECT_GT(f.t_capture, frames[i - 1].t_capture) << "frame " << i;
    }
    behind.push_back(f.t_arrival - f.t_capture);
    // The fake's clock is the host's: once the minimum-delay estimate has
    // seen a few frames, mapped time is the camera time plus at most a
    // loopback transfer.
    if (i >= 20) {
      EXPECT_GE(f.t_capture - f.t_capture_camera, 0.0) << "frame " << i;
      EXPECT_LT(f.t_capture - f.t_capture_camera, 0.005) << "frame " << i;
    }
  }
  std::nth_element(behind.begin(), behind.begin() + behind.size() / 2, behind.end());
  EXPECT_LT(behind[behind.size() / 2], 0.005) << "median arrival - capture";
}

TEST(GenicamCameraTest, InterruptUnblocksAGrab) {
  FakeGigeCamera cam(uniqueSerial("intr"));
  REQUIRE_FAKE(cam);
  GenicamSource src(cam.deviceId());
  src.applySettings({{"Width", "64"}, {"Height", "64"}, {"AcquisitionFrameRate", "0.2"}});  // a frame every 5 s
  ASSERT_EQ(grabFrames(src, 1).size(), 1u);
  {
    // The fake camera may send a second frame right after the first while
    // the new rate takes hold: drain until a grab finds the queue empty.
    Frame f;
    std::string why;
    for (int i = 0; i < 5 && src.grab(f, 0.5, why) == GrabStatus::Frame; ++i) {
    }
  }
  // A frame may still arrive within the 300 ms on a loaded machine (the
  // fake camera's timer): then the wait is tried again. Without interrupt()
  // every try ends only with a frame, 5 s later.
  GrabStatus status = GrabStatus::Frame;
  for (int attempt = 0; attempt < 3 && status == GrabStatus::Frame; ++attempt) {
    auto waiting = std::async(std::launch::async, [&] {
      Frame f;
      std::string why;
      return src.grab(f, 60.0, why);
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    src.interrupt();
    ASSERT_EQ(waiting.wait_for(std::chrono::seconds(30)), std::future_status::ready);
    status = waiting.get();
  }
  EXPECT_EQ(status, GrabStatus::Timeout) << "interrupt() ends the wait before the next frame";
}

TEST(GenicamCameraTest, GvcpProbeSeesWhetherTheCameraAnswers) {
  FakeGigeCamera cam(uniqueSerial("ping"));
  REQUIRE_FAKE(cam);
  EXPECT_TRUE(gvcpCameraAnswers("127.0.0.1", 1.0, 3));
  cam.stop();
  EXPECT_FALSE(gvcpCameraAnswers("127.0.0.1", 0.2, 2));
  EXPECT_FALSE(gvcpCameraAnswers("not an address"));
}

TEST(GenicamCameraTest, CameraGoneIsLostAndReconnectResumesWithTheSameSettings) {
  FakeGigeCamera cam(uniqueSerial("lost"));
  REQUIRE_FAKE(cam);
  GenicamSource src(cam.deviceId());
  src.applySettings({{"Width", "320"}, {"Height", "200"}, {"GainRaw", "2"}});
  ASSERT_EQ(grabFrames(src, 5).size(), 5u);

  cam.stop();  // unplugged
  Frame f;
  std::string why;
  GrabStatus s = GrabStatus::Timeout;
  const auto lost_limit = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (std::chrono::steady_clock::now() < lost_limit && (s == GrabStatus::Timeout || s == GrabStatus::Frame))
    s = src.grab(f, 0.5, why);
  ASSERT_EQ(s, GrabStatus::Lost) << why;
  EXPECT_NE(why.find("genicam://" + cam.deviceId()), std::string::npos) << why;
  EXPECT_NE(why.find("does not answer"), std::string::npos) << why;
  EXPECT_EQ(src.grab(f, 0.1, why), GrabStatus::Lost) << "stays lost until reconnect";
  EXPECT_FALSE(src.reconnect(why)) << "the camera is still gone";
  EXPECT_NE(why.find("still gone"), std::string::npos) << why;

  cam.start();  // plugged back in
  ASSERT_TRUE(cam.running());
  bool back = false;
  const auto back_limit = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!back && std::chrono::steady_clock::now() < back_limit) {
    back = src.reconnect(why);
    if (!back) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ASSERT_TRUE(back) << why;
  const auto frames = grabFrames(src, 5);
  ASSERT_EQ(frames.size(), 5u);
  EXPECT_EQ(frames[0].image.cols, 320) << "settings re-applied";
  EXPECT_EQ(frames[0].image.rows, 200);
  EXPECT_NE(src.describe().find("320x200"), std::string::npos) << src.describe();
}

}  // namespace
}  // namespace dv

// Where detections go when the disk fills mid-run: the SSL log stops with
// one warning naming the file, while every later detection still goes out
// (JSONL here; the publisher takes the same path).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/packet_outputs.h"
#include "geometry/geometry_io.h"
#include "temp_dir.h"

namespace dv::app {
namespace {

// About 30 KB serialized: a few of them overflow the log's 128 KiB buffer,
// so the write fails inside the run, not only at the close.
ssl::SSL_WrapperPacket bigPacket(uint32_t frame) {
  ssl::SSL_WrapperPacket p;
  auto* d = p.mutable_detection();
  d->set_frame_number(frame);
  d->set_t_capture(1.0);
  d->set_t_sent(1.0);
  d->set_camera_id(0);
  for (int i = 0; i < 1000; ++i) {
    auto* r = d->add_robots_yellow();
    r->set_confidence(1);
    r->set_x(float(i));
    r->set_y(float(-i));
    r->set_pixel_x(float(i));
    r->set_pixel_y(float(i));
  }
  return p;
}

TEST(PacketOutputs, FullDiskStopsTheLogOnceAndDetectionsGoOn) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  TempDir dir("dv_outputs_full");
  OutputOptions o;
  o.publish = false;
  o.ssl_log = "/dev/full";
  o.jsonl = dir.file("det.jsonl");
  o.who = "test";
  PacketOutputs outputs(o, toProto(loadGeometry(std::string(DV_SOURCE_DIR) + "/config/fields/division_b.json")));
  ::testing::internal::CaptureStderr();
  for (uint32_t i = 0; i < 20; ++i) ASSERT_NO_THROW(outputs.detection(bigPacket(i)));
  const std::string during = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(outputs.recordingFailure().find("/dev/full"), std::string::npos) << outputs.recordingFailure();
  EXPECT_NE(during.find("test: warning: recording stopped: /dev/full"), std::string::npos) << during;
  EXPECT_NE(during.find("No space left on device"), std::string::npos) << during;
  EXPECT_EQ(during.find("recording stopped", during.find("recording stopped") + 20), std::string::npos) << during;
  ASSERT_NO_THROW(outputs.finish());
  EXPECT_NE(outputs.describe().find("recording stopped: /dev/full"), std::string::npos) << outputs.describe();
  std::ifstream in(dir.file("det.jsonl"));
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, 20);
}

}  // namespace
}  // namespace dv::app

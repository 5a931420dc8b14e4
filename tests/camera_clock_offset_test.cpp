// The camera-to-host clock mapping: minimum of (arrival - camera time) over
// a sliding window.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "camera/clock_offset.h"
#include "camera/frame_id_gap.h"
#include "camera/receive_buffer.h"

namespace dv {
namespace {

TEST(ClockOffsetTest, EstimatesTheSmallestDelayAndNeverMapsAfterArrival) {
  ClockOffset clock;
  std::mt19937 rng(7);
  std::exponential_distribution<double> jitter(1.0 / 0.002);  // mean 2 ms above the floor
  const double true_offset = 1.7e9, floor = 0.0004;
  double previous = -1;
  for (int i = 0; i < 600; ++i) {
    const double camera = 100.0 + i / 60.0;
    const double arrival = camera + true_offset + floor + jitter(rng);
    const double t = clock.map(camera, arrival);
    EXPECT_LE(t, arrival);
    if (previous > 0) {
      EXPECT_GT(t, previous) << "frame " << i;
    }
    previous = t;
    if (i > 100) {
      EXPECT_NEAR(t, camera + true_offset + floor, 0.0005) << "frame " << i;
    }
  }
}

TEST(ClockOffsetTest, FollowsDriftBetweenTheClocks) {
  ClockOffset clock(2.0);
  const double drift = 50e-6;  // the camera's clock runs 50 ppm slow
  for (int i = 0; i < 60 * 120; ++i) {
    const double camera = i / 60.0;
    const double arrival = 1000 + camera * (1 + drift) + 0.001 + ((i % 7) ? 0.003 : 0.0);
    const double t = clock.map(camera, arrival);
    // After two minutes the offset moved by 6 ms; the window keeps up.
    if (i > 600) {
      EXPECT_NEAR(t, 1000 + camera * (1 + drift) + 0.001, 2.0 * drift + 1e-6) << "frame " << i;
    }
  }
}

TEST(ClockOffsetTest, ACameraClockJumpStartsAfresh) {
  ClockOffset clock;
  for (int i = 0; i < 100; ++i) clock.map(5000 + i / 60.0, 9000 + i / 60.0);
  EXPECT_NEAR(clock.offset(), 4000, 1e-6);
  // Camera restarted: its clock begins again near zero.
  const double t = clock.map(0.5, 9002.0);
  EXPECT_DOUBLE_EQ(t, 9002.0);
  EXPECT_EQ(clock.samples(), 1u);
  EXPECT_NEAR(clock.map(0.5 + 1 / 60.0, 9002.0 + 1 / 60.0 + 0.001), 9002.0 + 1 / 60.0, 1e-9);
}

TEST(ClockOffsetTest, OldSamplesLeaveTheWindow) {
  ClockOffset clock(1.0);
  clock.map(0.0, 10.0);  // an early frame with an offset of 10.0
  for (int i = 1; i <= 120; ++i) clock.map(i / 60.0, i / 60.0 + 10.5);  // later ones 10.5
  EXPECT_NEAR(clock.offset(), 10.5, 1e-9) << "the 10.0 sample is older than the window";
}

TEST(FrameIdGapTest, CountsMissingIdsAcrossTheSixteenBitWrap) {
  EXPECT_EQ(missedFrameIds(0, 17), 0u) << "first frame";
  EXPECT_EQ(missedFrameIds(5, 6), 0u);
  EXPECT_EQ(missedFrameIds(5, 9), 3u);
  EXPECT_EQ(missedFrameIds(65535, 1), 0u) << "GigE ids skip 0";
  EXPECT_EQ(missedFrameIds(65534, 2), 2u);
  EXPECT_EQ(missedFrameIds(40000, 3), 0u) << "a restart, not a wrap";
  EXPECT_EQ(missedFrameIds(1u << 20, 5), 0u) << "64-bit ids going back: a restart";
}

TEST(ReceiveBufferTest, SaysWhenTheSystemCapsTheStreamBuffer) {
  EXPECT_EQ(rmemCapMessage("genicam://cam", 8 << 20, 16 << 20), "");
  EXPECT_EQ(rmemCapMessage("genicam://cam", 8 << 20, -1), "") << "unknown cap: nothing to say";
  const std::string m = rmemCapMessage("genicam://cam", 20000000, 212992);
  EXPECT_NE(m.find("genicam://cam"), std::string::npos) << m;
  EXPECT_NE(m.find("212992"), std::string::npos) << m;
  EXPECT_NE(m.find("sysctl -w net.core.rmem_max=20000000"), std::string::npos) << m;
  EXPECT_GE(streamSocketBufferBytes(2448 * 2048), 3u * 2448 * 2048) << "room for a few frames";
}

}  // namespace
}  // namespace dv

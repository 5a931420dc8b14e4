// Detections -> SSL_DetectionFrame: every field the league reads, team split,
// and a message that stays valid on the wire when reused.
#include <gtest/gtest.h>

#include "detection/detection_frame.h"

namespace dv {
namespace {

Detections sample() {
  Detections d;
  BallDetection b;
  b.position = {100, -200, 21.5};
  b.confidence = 0.9f;
  b.pixel = {640.5, 480.25};
  d.balls.push_back(b);
  RobotDetection y;
  y.team = Team::Yellow;
  y.id = 3;
  y.position = {1000, 500};
  y.orientation = -1.25;
  y.height = 145;
  y.confidence = 0.8f;
  y.pixel = {10, 20};
  RobotDetection bl = y;
  bl.team = Team::Blue;
  bl.id = 11;
  bl.position = {-700, 0};
  d.robots = {y, bl};
  return d;
}

TEST(IoDetectionFrame, FillsEveryFieldAndSplitsTeams) {
  ssl::SSL_DetectionFrame f;
  fillDetectionFrame(sample(), {2, 17, 1.5, 1.503}, f);
  ASSERT_TRUE(f.IsInitialized()) << f.InitializationErrorString();
  EXPECT_EQ(f.camera_id(), 2u);
  EXPECT_EQ(f.frame_number(), 17u);
  EXPECT_DOUBLE_EQ(f.t_capture(), 1.5);
  EXPECT_DOUBLE_EQ(f.t_sent(), 1.503);
  ASSERT_EQ(f.balls_size(), 1);
  EXPECT_FLOAT_EQ(f.balls(0).x(), 100);
  EXPECT_FLOAT_EQ(f.balls(0).y(), -200);
  EXPECT_FLOAT_EQ(f.balls(0).z(), 21.5);
  EXPECT_FLOAT_EQ(f.balls(0).pixel_x(), 640.5);
  EXPECT_FLOAT_EQ(f.balls(0).confidence(), 0.9f);
  ASSERT_EQ(f.robots_yellow_size(), 1);
  ASSERT_EQ(f.robots_blue_size(), 1);
  const auto& y = f.robots_yellow(0);
  EXPECT_EQ(y.robot_id(), 3u);
  EXPECT_FLOAT_EQ(y.orientation(), -1.25);
  EXPECT_FLOAT_EQ(y.height(), 145);
  EXPECT_FLOAT_EQ(y.pixel_y(), 20);
  EXPECT_FLOAT_EQ(y.confidence(), 0.8f);
  EXPECT_EQ(f.robots_blue(0).robot_id(), 11u);
  EXPECT_FLOAT_EQ(f.robots_blue(0).x(), -700);
}

TEST(IoDetectionFrame, ReuseClearsThePreviousFrame) {
  ssl::SSL_WrapperPacket p;
  fillDetectionPacket(sample(), {0, 0, 0, 0}, p);
  fillDetectionPacket(Detections{}, {0, 1, 0.1, 0.1}, p);
  EXPECT_EQ(p.detection().balls_size(), 0);
  EXPECT_EQ(p.detection().robots_yellow_size(), 0);
  EXPECT_EQ(p.detection().frame_number(), 1u);
  EXPECT_FALSE(p.has_geometry());
  ssl::SSL_WrapperPacket back;
  ASSERT_TRUE(back.ParseFromString(p.SerializeAsString()));
  EXPECT_EQ(back.detection().frame_number(), 1u);
}

}  // namespace
}  // namespace dv

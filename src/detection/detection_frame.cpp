#include "detection/detection_frame.h"

namespace dv {

namespace {

void fillRobot(const RobotDetection& r, ssl::SSL_DetectionRobot& out) {
  out.set_confidence(r.confidence);
  out.set_robot_id(static_cast<uint32_t>(r.id));
  out.set_x(static_cast<float>(r.position.x));
  out.set_y(static_cast<float>(r.position.y));
  out.set_orientation(static_cast<float>(r.orientation));
  out.set_pixel_x(static_cast<float>(r.pixel.u));
  out.set_pixel_y(static_cast<float>(r.pixel.v));
  out.set_height(static_cast<float>(r.height));
}

}  // namespace

void fillDetectionFrame(const Detections& detections, const FrameStamp& stamp,
                        ssl::SSL_DetectionFrame& out) {
  out.Clear();  // keeps the repeated fields' element storage for reuse
  out.set_frame_number(stamp.frame_number);
  out.set_t_capture(stamp.t_capture);
  out.set_t_sent(stamp.t_sent);
  if (stamp.t_capture_camera >= 0) out.set_t_capture_camera(stamp.t_capture_camera);
  out.set_camera_id(stamp.camera_id);
  for (const BallDetection& b : detections.balls) {
    ssl::SSL_DetectionBall* ball = out.add_balls();
    ball->set_confidence(b.confidence);
    ball->set_x(static_cast<float>(b.position.x));
    ball->set_y(static_cast<float>(b.position.y));
    ball->set_z(static_cast<float>(b.position.z));
    ball->set_pixel_x(static_cast<float>(b.pixel.u));
    ball->set_pixel_y(static_cast<float>(b.pixel.v));
  }
  for (const RobotDetection& r : detections.robots) {
    fillRobot(r, r.team == Team::Yellow ? *out.add_robots_yellow() : *out.add_robots_blue());
  }
}

void fillDetectionPacket(const Detections& detections, const FrameStamp& stamp,
                         ssl::SSL_WrapperPacket& out, ssl::SSL_Source source) {
  out.clear_geometry();
  out.set_source(source);
  fillDetectionFrame(detections, stamp, *out.mutable_detection());
}

}  // namespace dv

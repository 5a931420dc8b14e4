#pragma once
// Detections of one camera frame -> the league's SSL_DetectionFrame, and the
// wrapper packet that carries it on the wire and in logs.
#include <cstdint>

#include "detection/detector.h"
#include "dotvision/ssl_wrapper.pb.h"

namespace dv {

struct FrameStamp {
  uint32_t camera_id = 0;
  uint32_t frame_number = 0;  // per camera, counting from 0
  double t_capture = 0;       // Unix s, end of exposure
  double t_sent = 0;          // Unix s
  double t_capture_camera = -1;  // s on the camera's own clock; < 0: none (left out of the packet)
};

// Clears `out` (keeping its storage) and fills every required field plus
// robot_id, orientation, height and ball z. Robots are split by team; the
// order of each list is the detector's (confidence, highest first).
void fillDetectionFrame(const Detections& detections, const FrameStamp& stamp,
                        ssl::SSL_DetectionFrame& out);

// The same into a wrapper packet without geometry. dotvision stands in for
// SSL-Vision on the league's port, so that is the default source.
void fillDetectionPacket(const Detections& detections, const FrameStamp& stamp,
                         ssl::SSL_WrapperPacket& out,
                         ssl::SSL_Source source = ssl::SSL_SOURCE_SSL_VISION);

}  // namespace dv

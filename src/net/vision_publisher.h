#pragma once
// Sends dotvision's output the way ssl-vision does on the vision port:
// every detection frame in its own SSL_WrapperPacket (detection + source),
// and the geometry in separate wrappers (geometry + source), repeated every
// few seconds so late-joining clients learn the field and cameras.
#include <cstdint>
#include <limits>
#include <string>

#include "dotvision/ssl_wrapper.pb.h"
#include "net/multicast.h"

namespace dv {

struct VisionPublisherOptions {
  std::string group = "224.5.23.2";
  uint16_t port = 10006;
  std::string interface_addr;  // "" = route decides; "127.0.0.1" = this host only
  // ssl-vision's "Auto Publish / Interval"; <= 0 disables the repetition.
  double geometry_interval_s = 3.0;
  // Receivers expect SSL_SOURCE_SSL_VISION from the league's vision system;
  // dotvision stands in for it, so that is the default.
  ssl::SSL_Source source = ssl::SSL_SOURCE_SSL_VISION;
};

class VisionPublisher {
 public:
  // Throws InputError naming "udp <group>:<port>" if the socket cannot be
  // set up; nothing after construction throws.
  explicit VisionPublisher(const VisionPublisherOptions& options = {});

  // The frame to send next, to be filled in place (its buffers are reused
  // from frame to frame, so the hot path does not allocate once warm).
  ssl::SSL_DetectionFrame& detection() { return *detection_wrapper_.mutable_detection(); }
  // Sends detection() and clears it for the next frame. Returns false (and
  // the sender counts it) if the frame lacks required fields or the send
  // failed.
  bool sendDetection();
  // Convenience: copies `frame` into detection() and sends it.
  bool publishDetection(const ssl::SSL_DetectionFrame& frame);

  // Replaces the geometry; it is serialized once here, not per send.
  // Returns false if required fields are missing (nothing is stored then).
  bool setGeometry(const ssl::SSL_GeometryData& geometry);
  bool hasGeometry() const { return !geometry_bytes_.empty(); }
  // Sends the geometry now (false if none is set or the send failed).
  bool publishGeometry(double now_s);
  // Sends the geometry when geometry_interval_s has passed since the last
  // geometry send (or none was sent yet). now_s: any monotonic clock in
  // seconds. Returns whether it sent.
  bool publishGeometryIfDue(double now_s);

  const MulticastSender& sender() const { return sender_; }
  uint64_t droppedInvalid() const { return dropped_invalid_; }

 private:
  VisionPublisherOptions options_;
  MulticastSender sender_;
  ssl::SSL_WrapperPacket detection_wrapper_;
  std::string buffer_;
  std::string geometry_bytes_;
  double last_geometry_s_ = -std::numeric_limits<double>::infinity();
  uint64_t dropped_invalid_ = 0;
};

}  // namespace dv

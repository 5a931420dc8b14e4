#include "net/vision_publisher.h"

namespace dv {

VisionPublisher::VisionPublisher(const VisionPublisherOptions& options)
    : options_(options), sender_(options.group, options.port, options.interface_addr) {
  detection_wrapper_.set_source(options_.source);
  detection_wrapper_.mutable_detection();
}

bool VisionPublisher::sendDetection() {
  ssl::SSL_DetectionFrame& frame = detection();
  // A proto2 receiver rejects a packet with missing required fields, so
  // such a frame is not worth sending.
  if (!frame.IsInitialized()) {
    ++dropped_invalid_;
    frame.Clear();
    return false;
  }
  // SerializeToString reuses buffer_'s capacity.
  detection_wrapper_.SerializeToString(&buffer_);
  frame.Clear();  // keeps the allocated balls/robots for the next frame
  return sender_.send(buffer_);
}

bool VisionPublisher::publishDetection(const ssl::SSL_DetectionFrame& frame) {
  detection().CopyFrom(frame);
  return sendDetection();
}

bool VisionPublisher::setGeometry(const ssl::SSL_GeometryData& geometry) {
  if (!geometry.IsInitialized()) return false;
  ssl::SSL_WrapperPacket wrapper;
  *wrapper.mutable_geometry() = geometry;
  wrapper.set_source(options_.source);
  geometry_bytes_ = wrapper.SerializeAsString();
  return true;
}

bool VisionPublisher::publishGeometry(double now_s) {
  if (geometry_bytes_.empty()) return false;
  last_geometry_s_ = now_s;
  return sender_.send(geometry_bytes_);
}

bool VisionPublisher::publishGeometryIfDue(double now_s) {
  if (geometry_bytes_.empty()) return false;
  const bool never_sent = last_geometry_s_ == -std::numeric_limits<double>::infinity();
  const bool repeat_due =
      options_.geometry_interval_s > 0 && now_s - last_geometry_s_ >= options_.geometry_interval_s;
  if (!never_sent && !repeat_due) return false;
  return publishGeometry(now_s);
}

}  // namespace dv

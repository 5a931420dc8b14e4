#pragma once
// V4L2 capture devices (webcams, HDMI grabbers) as the kernel lists them,
// asked directly through the V4L2 ioctls, for `dotvision cameras` and for
// the messages of a source that cannot be opened.
#include <optional>
#include <string>
#include <vector>

namespace dv {

struct V4l2Device {
  std::string path;                  // "/dev/video0"
  std::string name;                  // the driver's card name, "HD Pro Webcam C920"
  std::vector<std::string> formats;  // capture pixel formats, "MJPG (Motion-JPEG)", "YUYV (YUYV 4:2:2)"
};

// Every /dev/video* that is a video capture device, sorted by number.
// Metadata and output nodes (a webcam's second node) are left out; devices
// that cannot be opened (permission) are listed with name "(cannot open:
// <reason>)" so the user sees why.
std::vector<V4l2Device> listV4l2Devices();

// The device at `path`, or nullopt where it is no V4L2 capture device.
// Never throws.
std::optional<V4l2Device> queryV4l2Device(const std::string& path);

// "/dev/video0 (HD Pro Webcam C920), /dev/video2 (...)" or "none".
std::string v4l2DeviceSummary(const std::vector<V4l2Device>& devices);

}  // namespace dv

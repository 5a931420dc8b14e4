#include "camera/v4l2_list.h"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

namespace dv {
namespace {

int retryIoctl(int fd, unsigned long request, void* arg) {
  int r;
  do r = ::ioctl(fd, request, arg);
  while (r == -1 && errno == EINTR);
  return r;
}

std::string fourcc(uint32_t code) {
  std::string s;
  for (int i = 0; i < 4; ++i) s += char((code >> (8 * i)) & 0xff);
  s.erase(s.find_last_not_of(' ') + 1);
  return s;
}

// The number in "videoN", for sorting video2 before video10; -1 otherwise.
long videoNumber(const std::string& path) {
  const std::string name = std::filesystem::path(path).filename().string();
  if (name.rfind("video", 0) != 0 || name.size() == 5) return -1;
  const std::string digits = name.substr(5);
  if (!std::all_of(digits.begin(), digits.end(), ::isdigit)) return -1;
  return std::stol(digits);
}

}  // namespace

std::optional<V4l2Device> queryV4l2Device(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  std::optional<V4l2Device> result;
  v4l2_capability cap{};
  if (retryIoctl(fd, VIDIOC_QUERYCAP, &cap) == 0) {
    // device_caps describes this node; capabilities the whole device.
    const uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
    if (caps & V4L2_CAP_VIDEO_CAPTURE) {
      V4l2Device d;
      d.path = path;
      d.name = reinterpret_cast<const char*>(cap.card);
      for (uint32_t i = 0;; ++i) {
        v4l2_fmtdesc fmt{};
        fmt.index = i;
        fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        if (retryIoctl(fd, VIDIOC_ENUM_FMT, &fmt) != 0) break;
        d.formats.push_back(fourcc(fmt.pixelformat) + " (" + reinterpret_cast<const char*>(fmt.description) +
                            ")");
      }
      result = std::move(d);
    }
  }
  ::close(fd);
  return result;
}

std::vector<V4l2Device> listV4l2Devices() {
  std::vector<std::string> paths;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/dev", ec)) {
    const std::string p = entry.path().string();
    if (videoNumber(p) >= 0) paths.push_back(p);
  }
  std::sort(paths.begin(), paths.end(),
            [](const std::string& a, const std::string& b) { return videoNumber(a) < videoNumber(b); });
  std::vector<V4l2Device> devices;
  for (const auto& p : paths) {
    if (auto d = queryV4l2Device(p)) {
      devices.push_back(std::move(*d));
    } else if (::access(p.c_str(), R_OK | W_OK) != 0) {
      devices.push_back({p, std::string("(cannot open: ") + std::strerror(errno) + ")", {}});
    }
  }
  return devices;
}

std::string v4l2DeviceSummary(const std::vector<V4l2Device>& devices) {
  if (devices.empty()) return "none";
  std::string s;
  for (const auto& d : devices) s += (s.empty() ? "" : ", ") + d.path + " (" + d.name + ")";
  return s;
}

}  // namespace dv

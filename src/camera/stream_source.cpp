#include "camera/stream_source.h"


#include <fcntl.h>
#include <linux/videodev2.h>
#include <spdlog/spdlog.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <opencv2/imgproc.hpp>

#include "camera/v4l2_list.h"
#include "core/clock.h"
#include "core/error.h"

namespace dv {
namespace {

constexpr int kOpenTimeout_ms = 5000;     // FFmpeg: connecting to a stream
constexpr int kReadTimeout_ms = 2000;     // FFmpeg: a read that gets no data ends the stream
constexpr double kMaxCaptureAge_s = 1.0;  // a mapped V4L2 time stamp older than this is not trusted

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

std::string numberText(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// ---- settings: GenICam names onto OpenCV properties ----

enum class Kind { Integer, Real, Mode };

struct SettingMap {
  const char* name;
  int property;  // cv::CAP_PROP_*, or -1: a V4L2 control set directly (v4l2_control)
  uint32_t v4l2_control;
  Kind kind;
  const char* unit;        // printed after the read-back value
  double scale;            // genicam value = property value * scale
  double off, continuous;  // Mode: property values for Off and Continuous
};

// V4L2 through OpenCV: exposure in 100 us steps (V4L2_CID_EXPOSURE_ABSOLUTE),
// auto exposure 1 = manual, 3 = aperture priority (V4L2_CID_EXPOSURE_AUTO).
// OpenCV has no property for V4L2_CID_AUTOGAIN, so GainAuto goes to the device.
const SettingMap kSettings[] = {
    {"Width", cv::CAP_PROP_FRAME_WIDTH, 0, Kind::Integer, "px", 1, 0, 0},
    {"Height", cv::CAP_PROP_FRAME_HEIGHT, 0, Kind::Integer, "px", 1, 0, 0},
    {"AcquisitionFrameRate", cv::CAP_PROP_FPS, 0, Kind::Real, "fps", 1, 0, 0},
    {"ExposureTime", cv::CAP_PROP_EXPOSURE, 0, Kind::Real, "us", 100, 0, 0},
    {"ExposureAuto", cv::CAP_PROP_AUTO_EXPOSURE, 0, Kind::Mode, "", 1, 1, 3},
    {"Gain", cv::CAP_PROP_GAIN, 0, Kind::Real, "device units", 1, 0, 0},
    {"GainAuto", -1, V4L2_CID_AUTOGAIN, Kind::Mode, "", 1, 0, 1},
    {"BalanceWhiteAuto", cv::CAP_PROP_AUTO_WB, 0, Kind::Mode, "", 1, 0, 1},
    {"BalanceWhiteTemperature", cv::CAP_PROP_WB_TEMPERATURE, 0, Kind::Real, "K", 1, 0, 0},
};

std::string mappedNames() {
  std::string s;
  for (const auto& m : kSettings) s += (s.empty() ? "" : ", ") + std::string(m.name);
  return s;
}

bool equalsIgnoreCase(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// Sets and reads back one V4L2 control on the device node (a second open of
// a device is allowed for controls). false and why on failure.
bool setV4l2Control(const std::string& device, uint32_t id, int value, int& read_back, std::string& why) {
  if (device.empty()) {
    why = "a network stream has no V4L2 controls";
    return false;
  }
  const int fd = ::open(device.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    why = std::string("cannot open the device: ") + std::strerror(errno);
    return false;
  }
  v4l2_control c{};
  c.id = id;
  c.value = value;
  bool ok = ::ioctl(fd, VIDIOC_S_CTRL, &c) == 0;
  if (!ok) why = std::string("the device refuses it: ") + std::strerror(errno);
  if (ok) {
    ok = ::ioctl(fd, VIDIOC_G_CTRL, &c) == 0;
    if (!ok) why = std::string("cannot read it back: ") + std::strerror(errno);
    read_back = c.value;
  }
  ::close(fd);
  return ok;
}

}  // namespace

bool isStreamSpec(const std::string& spec) {
  return startsWith(spec, "v4l2://") || startsWith(spec, "/dev/video") || startsWith(spec, "rtsp://") ||
         startsWith(spec, "http://") || startsWith(spec, "https://");
}

StreamSource::StreamSource(const std::string& spec) : spec_(spec) {
  // FFmpeg would print a line per failed connection attempt, i.e. every
  // second while a camera is away; our Lost / reconnect messages say it once.
  // An operator's own choice of level is kept.
  ::setenv("OPENCV_FFMPEG_LOGLEVEL", "8", 0);  // AV_LOG_FATAL
  if (startsWith(spec, "v4l2://")) {
    device_ = spec.substr(7);
    if (device_.empty()) throw InputError(spec, "no device path (write v4l2:///dev/video0)");
  } else if (startsWith(spec, "/dev/video")) {
    device_ = spec;
  } else {
    url_ = spec;
  }
  std::string why;
  if (!open(why)) throw InputError(spec_, why);
}

StreamSource::~StreamSource() { stopReader(); }

bool StreamSource::open(std::string& why) {
  capture_.release();
  try {
    if (!device_.empty()) {
      struct stat st {};
      if (::stat(device_.c_str(), &st) != 0) {
        why = "no such device; V4L2 devices here: " + v4l2DeviceSummary(listV4l2Devices());
        return false;
      }
      if (!queryV4l2Device(device_)) {
        why = "not a V4L2 capture device (or no permission to open it); V4L2 devices here: " +
              v4l2DeviceSummary(listV4l2Devices());
        return false;
      }
      capture_.open(device_, cv::CAP_V4L2);
    } else {
      capture_.open(
          url_, cv::CAP_FFMPEG,
          {cv::CAP_PROP_OPEN_TIMEOUT_MSEC, kOpenTimeout_ms, cv::CAP_PROP_READ_TIMEOUT_MSEC, kReadTimeout_ms});
    }
  } catch (const cv::Exception& e) {
    why = std::string("OpenCV could not open it: ") + e.what();
    return false;
  }
  if (!capture_.isOpened()) {
    why = device_.empty() ? "the stream does not answer or is not a video stream (OpenCV's FFmpeg backend, " +
                                std::to_string(kOpenTimeout_ms / 1000) + " s timeout)"
                          : "OpenCV's V4L2 backend cannot open it (in use by another program?)";
    return false;
  }
  updateDescription();
  return true;
}

void StreamSource::updateDescription() {
  const std::string text = spec_ + " (" + std::to_string(int(capture_.get(cv::CAP_PROP_FRAME_WIDTH))) + "x" +
                           std::to_string(int(capture_.get(cv::CAP_PROP_FRAME_HEIGHT))) + ", " +
                           numberText(capture_.get(cv::CAP_PROP_FPS)) + " fps)";
  std::lock_guard<std::mutex> lock(mutex_);
  description_ = text;
}

std::string StreamSource::describe() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return description_;
}

SourceCounters StreamSource::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

void StreamSource::interrupt() {
  std::lock_guard<std::mutex> lock(mutex_);
  interrupted_ = true;
  changed_.notify_all();
}

void StreamSource::startReader() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = false;
    last_frame_steady_ = steadySeconds();
  }
  reader_ = std::thread([this] { readLoop(); });
  reader_running_ = true;
}

void StreamSource::stopReader() {
  if (!reader_running_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  reader_.join();  // at most one read: FFmpeg's read timeout, V4L2's select timeout
  reader_running_ = false;
  std::lock_guard<std::mutex> lock(mutex_);
  stop_ = false;
}

void StreamSource::readLoop() {
  cv::Mat back, converted;  // back: being read; rotates with newest_ and the caller's Frame
  uint32_t index = 0;
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stop_) return;
    }
    bool ok = false;
    std::string error;
    try {
      ok = capture_.read(back);
    } catch (const cv::Exception& e) {
      error = e.what();
    }
    const double arrival = unixSeconds();
    const double steady = steadySeconds();
    if (!ok || back.empty()) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stop_) return;
      reader_done_ = true;
      lost_reason_ = error.empty() ? "the stream ended or failed (no frame from the " +
                                         std::string(device_.empty() ? "FFmpeg" : "V4L2") + " backend)"
                                   : "reading failed: " + error;
      changed_.notify_all();
      return;
    }
    const uint32_t this_index = index++;
    if (back.type() != CV_8UC3) {
      if (back.type() == CV_8UC1) {
        cv::cvtColor(back, converted, cv::COLOR_GRAY2BGR);
      } else if (back.type() == CV_8UC4) {
        cv::cvtColor(back, converted, cv::COLOR_BGRA2BGR);
      } else {
        std::lock_guard<std::mutex> lock(mutex_);
        ++counters_.skipped;
        continue;
      }
      cv::swap(back, converted);
    }
    // The backend's time stamp: V4L2 gives the driver's buffer time on the
    // monotonic clock (what steady_clock reads on Linux), FFmpeg the
    // stream's own time.
    const double backend_ms = capture_.get(cv::CAP_PROP_POS_MSEC);
    const double t_camera = std::isfinite(backend_ms) && backend_ms > 0 ? backend_ms * 1e-3 : -1;
    double t_capture = arrival;
    if (!device_.empty() && t_camera > 0) {
      const double mapped = t_camera + (arrival - steady);
      if (mapped <= arrival && mapped > arrival - kMaxCaptureAge_s) t_capture = mapped;
    }

    std::lock_guard<std::mutex> lock(mutex_);
    if (t_capture <= last_t_capture_) t_capture = last_t_capture_ + 1e-6;  // clock stepped back
    last_t_capture_ = t_capture;
    if (fresh_) ++counters_.lost_frames;  // the previous one was never taken: latest wins
    cv::swap(back, newest_);
    fresh_ = true;
    newest_t_capture_ = t_capture;
    newest_t_camera_ = t_camera;
    newest_t_arrival_ = std::max(arrival, t_capture);
    newest_index_ = this_index;
    last_frame_steady_ = steady;
    changed_.notify_all();
  }
}

GrabStatus StreamSource::grab(Frame& f, double timeout_s, std::string& why) {
  bool start = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    start = !reader_running_ && !lost_ && !reader_done_;
  }
  if (start) startReader();

  std::unique_lock<std::mutex> lock(mutex_);
  const double deadline = steadySeconds() + timeout_s;
  for (;;) {
    if (interrupted_) {
      interrupted_ = false;
      return GrabStatus::Timeout;
    }
    if (lost_) {
      why = lost_reason_;
      return GrabStatus::Lost;
    }
    if (fresh_) {
      cv::swap(f.image, newest_);
      fresh_ = false;
      f.format = PixelFormat::Bgr8;
      f.t_capture = newest_t_capture_;
      f.t_capture_camera = newest_t_camera_;
      f.t_arrival = newest_t_arrival_;
      f.index = newest_index_;
      char number[16];
      const int n = std::snprintf(number, sizeof number, "#%u", newest_index_);
      f.name.assign(spec_);
      f.name.append(number, size_t(n));
      ++counters_.frames;
      return GrabStatus::Frame;
    }
    if (reader_done_) {
      lost_ = true;
      why = lost_reason_;
      return GrabStatus::Lost;
    }
    const double now = steadySeconds();
    const double stall_at = last_frame_steady_ + kStallTimeout_s;
    if (now >= stall_at) {
      lost_ = true;
      stop_ = true;  // the reader ends when its read returns; reconnect() joins it
      lost_reason_ = "no frame for " + numberText(kStallTimeout_s) + " s";
      why = lost_reason_;
      return GrabStatus::Lost;
    }
    if (now >= deadline) return GrabStatus::Timeout;
    changed_.wait_for(lock, std::chrono::duration<double>(std::min(deadline, stall_at) - now));
  }
}

bool StreamSource::reconnect(std::string& why) {
  stopReader();
  if (!open(why)) return false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    lost_ = false;
    reader_done_ = false;
    fresh_ = false;
    lost_reason_.clear();
  }
  for (const auto& s : settings_) {
    try {
      spdlog::info("{}: re-applied {}", spec_, applyOne(s));
    } catch (const InputError& e) {
      spdlog::warn("{}", e.what());  // the camera is back; a refused setting does not keep it away
    }
  }
  return true;
}

std::vector<std::string> StreamSource::applySettings(const std::vector<CameraSetting>& settings) {
  std::vector<std::string> lines;
  if (settings.empty()) return lines;
  stopReader();  // VideoCapture is not thread-safe; grab() starts the reader again
  for (const auto& s : settings) {
    lines.push_back(applyOne(s));
    // Keep the latest value per name, in the order last given, for reconnect().
    settings_.erase(std::remove_if(settings_.begin(), settings_.end(),
                                   [&](const CameraSetting& old) { return old.name == s.name; }),
                    settings_.end());
    settings_.push_back(s);
  }
  return lines;
}

std::string StreamSource::applyOne(const CameraSetting& s) {
  const SettingMap* map = nullptr;
  for (const auto& m : kSettings) {
    if (s.name == m.name) map = &m;
  }
  if (!map)
    throw InputError(spec_, "camera setting '" + s.name +
                                "' does not map to this V4L2/stream source; those that do: " + mappedNames());
  const std::string what = "camera setting " + s.name + "=" + s.value;

  double want = 0;  // in property units
  if (map->kind == Kind::Mode) {
    if (equalsIgnoreCase(s.value, "Off")) {
      want = map->off;
    } else if (equalsIgnoreCase(s.value, "Continuous")) {
      want = map->continuous;
    } else {
      throw InputError(spec_, what + ": the value must be Off or Continuous");
    }
  } else {
    size_t used = 0;
    double v = 0;
    try {
      v = std::stod(s.value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != s.value.size() || !std::isfinite(v))
      throw InputError(spec_, what + ": '" + s.value + "' is not a number");
    if (map->kind == Kind::Integer && (v != std::floor(v) || v <= 0))
      throw InputError(spec_, what + ": must be a positive whole number");
    want = v / map->scale;
  }

  double got = 0;
  if (map->property < 0) {
    int read_back = 0;
    std::string why;
    if (!setV4l2Control(device_, map->v4l2_control, int(want), read_back, why))
      throw InputError(spec_, what + " refused: " + why);
    got = read_back;
  } else {
    bool ok = false;
    try {
      ok = capture_.set(map->property, want);
    } catch (const cv::Exception&) {
      ok = false;
    }
    if (!ok)
      throw InputError(spec_, what + " refused: " +
                                  (device_.empty() ? "a network stream is set at its sender, not here"
                                                   : "the device or OpenCV's V4L2 backend does not take it"));
    got = capture_.get(map->property);
  }
  const double tolerance = map->kind == Kind::Real ? 0.01 * std::abs(want) + 1e-9 : 0.5;
  if (!(std::abs(got - want) <= tolerance))
    throw InputError(spec_, what + " refused: the device reads back " + numberText(got * map->scale) +
                                (map->unit[0] ? std::string(" ") + map->unit : std::string()));

  std::string line = std::string(map->name) + " = ";
  if (map->kind == Kind::Mode) {
    line += got == map->off ? "Off" : "Continuous";
  } else {
    line += numberText(got * map->scale) + " (" + map->unit + ")";
  }
  if (map->property == cv::CAP_PROP_FRAME_WIDTH || map->property == cv::CAP_PROP_FRAME_HEIGHT ||
      map->property == cv::CAP_PROP_FPS)
    updateDescription();
  return line;
}

}  // namespace dv

#include "io/camera_source.h"


#include <algorithm>
#include <chrono>
#include <thread>

#include "core/clock.h"
#include "core/error.h"

namespace dv {


CameraSetting parseCameraSetting(const std::string& item, const std::string& origin) {
  const size_t eq = item.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(origin, "camera setting '" + item + "' is not Name=Value (e.g. ExposureTime=4000)");
  auto trim = [](std::string t) {
    const size_t a = t.find_first_not_of(" \t"), b = t.find_last_not_of(" \t");
    return a == std::string::npos ? std::string() : t.substr(a, b - a + 1);
  };
  CameraSetting s{trim(item.substr(0, eq)), trim(item.substr(eq + 1))};
  if (s.name.empty()) throw InputError(origin, "camera setting '" + item + "' has no feature name");
  return s;
}

std::vector<std::string> CameraSource::applySettings(const std::vector<CameraSetting>& settings) {
  if (!settings.empty())
    throw InputError(describe(), "takes no camera settings (got '" + settings.front().name +
                                     "'): settings are for cameras");
  return {};
}

FileCameraSource::FileCameraSource(std::unique_ptr<FrameSource> source, bool realtime)
    : source_(std::move(source)), realtime_(realtime) {}

void FileCameraSource::interrupt() { interrupted_ = true; }

GrabStatus FileCameraSource::grab(Frame& f, double timeout_s, std::string& why) {
  if (!have_pending_) {
    const bool more = source_->next(pending_);
    if (skips_seen_ < source_->skipped().size()) {
      // Report one skip per call; the frame read (if any) waits for the next.
      const SkipRecord& r = source_->skipped()[skips_seen_++];
      why = r.name + ": " + r.reason;
      ++counters_.skipped;
      have_pending_ = more;
      return GrabStatus::Skipped;
    }
    if (!more) return GrabStatus::End;
    have_pending_ = true;
  }
  if (realtime_) {
    if (!started_) {
      started_ = true;
      first_t_ = pending_.t_capture;
      start_wall_ = steadySeconds();
    }
    double due = start_wall_ + (pending_.t_capture - first_t_);
    // Far behind (the first frame built the processor, or the machine
    // stalled): resume at the files' pace instead of bursting to catch up.
    if (steadySeconds() - due > 0.25) {
      start_wall_ += steadySeconds() - due;
      due = steadySeconds();
    }
    const double deadline = steadySeconds() + timeout_s;
    while (steadySeconds() < due) {
      if (interrupted_.exchange(false)) return GrabStatus::Timeout;
      const double now = steadySeconds();
      if (now >= deadline) return GrabStatus::Timeout;
      const double wait = std::min({due - now, deadline - now, 0.005});
      std::this_thread::sleep_for(std::chrono::duration<double>(wait));
    }
  }
  cv::swap(f.image, pending_.image);
  f.format = pending_.format;
  f.t_capture = pending_.t_capture;
  f.t_capture_camera = pending_.t_capture_camera;
  f.t_arrival = realtime_ ? unixSeconds() : 0;
  f.index = pending_.index;
  f.name.swap(pending_.name);
  have_pending_ = false;
  ++counters_.frames;
  return GrabStatus::Frame;
}

}  // namespace dv

#include "live/live_camera.h"

#include <pthread.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "core/clock.h"

namespace dv {

namespace {
std::string seconds(double s) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f s", s);
  return b;
}
}  // namespace

const char* sourceStateName(SourceState s) {
  switch (s) {
    case SourceState::Starting: return "starting";
    case SourceState::Running: return "running";
    case SourceState::NoFrames: return "no frames";
    case SourceState::Lost: return "lost";
    case SourceState::Ended: return "ended";
    case SourceState::Stopped: return "stopped";
  }
  return "?";
}

LiveCamera::LiveCamera(std::string name, std::unique_ptr<CameraSource> source, ProcessFn process, LogFn log,
                       LiveCameraOptions options)
    : name_(std::move(name)),
      source_(std::move(source)),
      process_(std::move(process)),
      log_(std::move(log)),
      options_(options) {}

LiveCamera::~LiveCamera() { stop(); }

namespace {
// "capture 0", "detect 0" in top -H and in /proc (names are cut at 15 bytes).
void nameThisThread(const char* role, const std::string& camera) {
  std::string n = std::string(role) + " " + (camera.rfind("camera ", 0) == 0 ? camera.substr(7) : camera);
  n.resize(std::min<size_t>(n.size(), 15));
  pthread_setname_np(pthread_self(), n.c_str());
}
}  // namespace

void LiveCamera::start() {
  capture_ = std::thread([this] {
    nameThisThread("capture", name_);
    captureLoop();
  });
  processing_ = std::thread([this] {
    nameThisThread("detect", name_);
    processLoop();
  });
}

void LiveCamera::stop() {
  stop_ = true;
  if (source_) source_->interrupt();
  // The capture thread closes the slot as it ends, after its last put, so
  // the processing thread takes that frame too: every frame delivered is
  // either processed or counted as dropped.
  if (capture_.joinable()) capture_.join();
  slot_.close();
  if (processing_.joinable()) processing_.join();
  std::lock_guard<std::mutex> lock(mutex_);
  if (counters_.state != SourceState::Ended) counters_.state = SourceState::Stopped;
}

LiveCounters LiveCamera::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

void LiveCamera::setState(SourceState s, const std::string& problem) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    counters_.state = s;
    if (!problem.empty()) counters_.last_problem = problem;
  }
  if (!problem.empty() && log_) log_(name_ + ": " + problem);
}

void LiveCamera::captureLoop() {
  Frame frame;
  std::string why;
  const bool live = source_->live();
  double last_frame = steadySeconds();
  double lost_since = 0;        // steady s when the camera was lost or went silent; 0: fine
  double fps_estimate = 0;      // frames per second before the gap
  double last_t_capture = 0;
  uint64_t skips_reported = 0;
  double skip_report_at = 0;
  while (!stop_) {
    const GrabStatus status = source_->grab(frame, options_.grab_timeout_s, why);
    const double now = steadySeconds();
    switch (status) {
      case GrabStatus::Frame: {
        if (last_t_capture > 0 && frame.t_capture > last_t_capture) {
          const double rate = 1.0 / (frame.t_capture - last_t_capture);
          fps_estimate = fps_estimate > 0 ? 0.9 * fps_estimate + 0.1 * rate : rate;
        }
        last_t_capture = frame.t_capture;
        if (lost_since > 0) {
          const double gap = now - lost_since;
          const uint64_t missed = static_cast<uint64_t>(gap * fps_estimate + 0.5);
          {
            std::lock_guard<std::mutex> lock(mutex_);
            counters_.gap_frames += missed;
          }
          setState(SourceState::Running, "camera back after " + seconds(gap) + " (about " +
                                             std::to_string(missed) + " frames lost)");
          lost_since = 0;
        } else if (counters().state != SourceState::Running) {
          setState(SourceState::Running, "");
        }
        last_frame = now;
        const bool dropped = live ? slot_.put(frame) : false;
        if (!live) {
          // Files unpaced: every frame is processed, so wait for the slot.
          while (!stop_ && !slot_.empty()) std::this_thread::sleep_for(std::chrono::microseconds(200));
          slot_.put(frame);
        }
        uint64_t frames_in;
        {
          std::lock_guard<std::mutex> lock(mutex_);
          frames_in = ++counters_.frames_in;
          if (dropped) ++counters_.dropped;
          counters_.last_frame_unix = unixSeconds();
        }
        // The first frame builds the processor (remap tables, up to a second):
        // wait for it, so the camera's first second is not counted as drops.
        if (frames_in == 1)
          while (!stop_ && counters().processed == 0 && !slot_.closed())
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        break;
      }
      case GrabStatus::Timeout:
        if (live && lost_since == 0 && now - last_frame > options_.stall_timeout_s) {
          lost_since = last_frame;
          setState(SourceState::NoFrames, "no frames for " + seconds(now - last_frame));
        }
        break;
      case GrabStatus::Skipped: {
        uint64_t total;
        {
          std::lock_guard<std::mutex> lock(mutex_);
          total = ++counters_.skipped;
          counters_.last_problem = "skipped: " + why;
        }
        // The first skip is reported at once, later ones at most once a second as a count.
        if (skips_reported == 0 || now - skip_report_at >= 1) {
          if (log_)
            log_(name_ + ": skipped " + why +
                 (total - skips_reported > 1 ? " (" + std::to_string(total - skips_reported) + " since the last report)"
                                             : ""));
          skips_reported = total;
          skip_report_at = now;
        }
        break;
      }
      case GrabStatus::Lost: {
        if (lost_since == 0) lost_since = last_frame;
        {
          std::lock_guard<std::mutex> lock(mutex_);
          ++counters_.losses;
        }
        setState(SourceState::Lost, "camera lost: " + why + "; retrying every " +
                                        seconds(options_.retry_interval_s));
        std::string retry_why;
        while (!stop_) {
          const double until = steadySeconds() + options_.retry_interval_s;
          while (!stop_ && steadySeconds() < until) std::this_thread::sleep_for(std::chrono::milliseconds(20));
          if (stop_) break;
          if (source_->reconnect(retry_why)) {
            std::lock_guard<std::mutex> lock(mutex_);
            ++counters_.reconnects;
            break;
          }
        }
        last_frame = steadySeconds();  // the stall clock restarts after a reconnect
        break;
      }
      case GrabStatus::End:
        setState(SourceState::Ended, "");
        stop_ = true;
        ended_pending_ = true;
        break;
    }
  }
  slot_.close();
}

void LiveCamera::processLoop() {
  Frame frame;
  while (true) {
    if (!slot_.take(frame, 0.1)) {
      if (slot_.closed()) break;
      continue;
    }
    process_(frame, unixSeconds());
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.processed;
  }
  if (ended_pending_) ended_ = true;
}

}  // namespace dv

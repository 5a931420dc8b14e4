#include "live/health_monitor.h"

#include <algorithm>
#include <cstdio>
#include <vector>

namespace dv {

namespace {
constexpr size_t kMinute = 60;  // updates kept (one a second)
constexpr size_t kRecent = 5;   // the newest seconds, compared with the rest

std::string fmt(const char* f, double a, double b = 0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}
}  // namespace

bool HealthMonitor::update(CameraStatus& s) {
  const LiveCounters& c = s.counters;
  history_.push_back({s.robots_per_frame, s.yellow_per_frame, s.blue_per_frame});
  while (history_.size() > kMinute) history_.pop_front();

  const uint64_t new_in = c.frames_in - std::min(c.frames_in, last_in_);
  const uint64_t new_dropped = c.dropped - std::min(c.dropped, last_dropped_);
  last_in_ = c.frames_in;
  last_dropped_ = c.dropped;
  Health h = Health::Ok;
  std::string kind, reason;
  if (c.state == SourceState::Lost) {
    h = Health::Lost, kind = "lost", reason = "camera lost: " + c.last_problem;
  } else if (c.state == SourceState::NoFrames || (c.state == SourceState::Starting && c.frames_in == 0)) {
    h = Health::Lost, kind = "no frames", reason = "no frames from the camera";
  } else if (c.processed == 0 && c.skipped > 0) {
    h = Health::Lost, kind = "refused", reason = "no frame could be processed: " + c.last_problem;
  } else if (c.processed == 0) {
    // Starting: the first frame builds the processor.
  } else if (s.fps_in > 0 && s.fps_out == 0) {
    h = Health::Degraded, kind = "stalled", reason = "frames arrive but none was processed in the last second";
  } else if (new_in >= 5 && new_dropped > 0.2 * new_in) {
    // Judged by the frames dropped since the last record, not by the two
    // rates, which differ by the frame in flight when the camera is slow.
    h = Health::Degraded, kind = "behind";
    reason = fmt("processing behind the camera: %.0f of %.0f frames dropped in the last second",
                 static_cast<double>(new_dropped), static_cast<double>(new_in));
  } else if (history_.size() > 2 * kRecent) {
    // Means over the older part of the minute and over the newest seconds.
    double old_y = 0, old_b = 0, new_y = 0, new_b = 0;
    std::vector<double> old_robots;
    const size_t n_old = history_.size() - kRecent;
    for (size_t i = 0; i < history_.size(); ++i) {
      const Second& x = history_[i];
      if (i < n_old) old_y += x.yellow, old_b += x.blue, old_robots.push_back(x.robots);
      else new_y += x.yellow, new_b += x.blue;
    }
    old_y /= n_old, old_b /= n_old, new_y /= kRecent, new_b /= kRecent;
    std::nth_element(old_robots.begin(), old_robots.begin() + old_robots.size() / 2, old_robots.end());
    const double old_median = old_robots[old_robots.size() / 2];
    double new_robots = 0;
    for (size_t i = n_old; i < history_.size(); ++i) new_robots += history_[i].robots;
    new_robots /= kRecent;
    if (old_y >= 1 && new_y < 0.05 && new_b >= 0.5) {
      h = Health::Degraded, kind = "yellow missing";
      reason = fmt("no yellow robot for %.0f s (there were %.1f per frame) while blue ones are seen", kRecent, old_y);
    } else if (old_b >= 1 && new_b < 0.05 && new_y >= 0.5) {
      h = Health::Degraded, kind = "blue missing";
      reason = fmt("no blue robot for %.0f s (there were %.1f per frame) while yellow ones are seen", kRecent, old_b);
    } else if (old_median >= 2 && new_robots < 0.6 * old_median) {
      h = Health::Degraded, kind = "fewer robots";
      reason = fmt("robots per frame fell from %.1f to %.1f", old_median, new_robots);
    }
  }
  s.health = h;
  s.health_reason = reason;
  const bool changed = first_ ? h != Health::Ok : (h != last_ || kind != last_kind_);
  first_ = false;
  last_ = h;
  last_kind_ = kind;
  return changed;
}

}  // namespace dv

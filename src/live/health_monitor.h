#pragma once
// Turns a camera's per-second status into a health state with its reason,
// from the evidence the record carries: the source's state, frames dropped
// behind the camera, a team that vanished while the other is still seen,
// and robots per frame falling against the last minute. The rules compare
// the camera with its own recent past, not with fixed counts, so a camera
// that sees half a field is judged against itself.
#include <deque>
#include <string>

#include "live/camera_status.h"

namespace dv {

class HealthMonitor {
 public:
  // Sets s.health and s.health_reason. Returns true when the state or its
  // reason's kind changed since the last call (log it once).
  bool update(CameraStatus& s);

 private:
  struct Second {
    double robots, yellow, blue;
  };
  std::deque<Second> history_;  // one per update, newest last, a minute long
  Health last_ = Health::Ok;
  std::string last_kind_;
  bool first_ = true;
  uint64_t last_in_ = 0, last_dropped_ = 0;  // counters at the previous update
};

}  // namespace dv

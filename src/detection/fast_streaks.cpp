#include "detection/fast_streaks.h"

#include <algorithm>
#include <cmath>

namespace dv {
namespace {
double distance(FieldMm a, FieldMm b) { return std::hypot(a.x - b.x, a.y - b.y); }
}  // namespace

void FastStreaks::begin(double t) {
  std::rotate(frames_.begin(), frames_.begin() + 1, frames_.end());
  frames_.back().t = t;
  frames_.back().n = 0;
}

void FastStreaks::add(FieldMm p) {
  Frame& f = frames_.back();
  if (f.n < kMaxPerFrame) f.at[f.n++] = p;
}

bool FastStreaks::slowNear(int k, FieldMm p, double t) const {
  const Frame& f = frames_[k];
  for (int i = 0; i < f.n; ++i)
    if (distance(p, f.at[i]) <= max_robot_speed_ * (t - f.t)) return true;
  return false;
}

double FastStreaks::confidence(FieldMm p) const {
  const int now = kFramesBefore;
  const double t = frames_[now].t;
  if (!(t > frames_[now - 1].t) || slowNear(now - 1, p, t)) return 0;
  double best = 0;
  for (int ka = now - 1; ka >= 1; --ka) {
    const Frame& a = frames_[ka];
    const double dt = t - a.t;
    if (!(dt > 0)) break;
    for (int i = 0; i < a.n; ++i) {
      const double step = distance(p, a.at[i]);
      if (step <= max_robot_speed_ * dt || step > max_ball_speed_ * dt) continue;
      if (slowNear(ka - 1, a.at[i], a.t)) continue;
      for (int kb = ka - 1; kb >= 0; --kb) {
        const Frame& b = frames_[kb];
        const double dt0 = a.t - b.t;
        if (!(dt0 > 0)) break;
        for (int j = 0; j < b.n; ++j) {
          const double step0 = distance(a.at[i], b.at[j]);
          if (step0 <= max_robot_speed_ * dt0 || step0 > max_ball_speed_ * dt0) continue;
          const double f = dt / dt0;
          const FieldMm predicted{a.at[i].x + f * (a.at[i].x - b.at[j].x), a.at[i].y + f * (a.at[i].y - b.at[j].y)};
          const double off = distance(p, predicted);
          if (off <= 2 * ball_radius_) best = std::max(best, 1 - off / step);
        }
      }
    }
  }
  return best;
}

}  // namespace dv

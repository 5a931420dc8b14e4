#include "detection/ball_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/robot_pattern.h"

namespace dv {
namespace {

double dist(const FieldMm& a, const FieldMm& b) { return std::hypot(a.x - b.x, a.y - b.y); }

// A gate's least radius (mm): a ball's blob moves by a few millimetres
// between frames even when the ball lies still.
constexpr double kMinGate = 30;
// The longest gap (s) a prediction spans and an unconfirmed track survives
// (flicker, occlusion).
constexpr double kMaxGap = 0.1;

}  // namespace

BallTracker::BallTracker(const BallTrackerOptions& o) : opt_(o) { tracks_.reserve(kMaxTracks); }

FieldMm BallTracker::reflectAtWalls(FieldMm from, FieldMm p) const {
  const double r = opt_.ball_radius;
  auto mirror = [](double v0, double v, double lo, double hi) {
    if (hi <= lo || v0 < lo || v0 > hi) return v;  // not between the walls
    if (v > hi) v = std::max(lo, 2 * hi - v);
    if (v < lo) v = std::min(hi, 2 * lo - v);
    return v;
  };
  const FieldRect& a = opt_.area;
  return {mirror(from.x, p.x, a.x_min + r, a.x_max - r), mirror(from.y, p.y, a.y_min + r, a.y_max - r)};
}

FieldMm BallTracker::straightOn(const BallTrack& bt, double dt) const {
  const double f = dt / (bt.t[1] - bt.t[0]);
  return reflectAtWalls(bt.pos[1], {bt.pos[1].x + f * (bt.pos[1].x - bt.pos[0].x),
                                    bt.pos[1].y + f * (bt.pos[1].y - bt.pos[0].y)});
}

void BallTracker::predict(double t, const FieldMm* robots, int n) {
  for (auto& bt : tracks_) {
    bt.predicted = bt.pos[1];
    const double dt = std::max(0.0, t - bt.t[1]);
    const double reach = opt_.max_ball_speed * std::min(dt, kMaxGap);
    if (bt.history >= 2 && bt.t[1] > bt.t[0]) {
      bt.predicted = straightOn(bt, dt);
      bt.gate = kMinGate + 0.5 * reach;
    } else {
      bt.gate = kMinGate + reach;
    }
    // Next to a robot the ball may have been kicked in any direction: the
    // track also takes what it could reach from its last position.
    bt.kick_gate = 0;
    const double touch = RobotPatternGeometry::kMaxRadius + opt_.ball_radius +
                         (opt_.max_ball_speed + opt_.max_robot_speed) * std::min(dt, kMaxGap);
    for (int i = 0; i < n; ++i)
      if (dist(bt.pos[1], robots[i]) < touch) bt.kick_gate = kMinGate + reach;
    bt.confirmed = false;
  }
}

void BallTracker::onCourse(const BallTrack& bt, FieldMm from, FieldMm p, double& along, double& across) const {
  const double dx = bt.pos[1].x - bt.pos[0].x, dy = bt.pos[1].y - bt.pos[0].y;
  const double step = std::hypot(dx, dy);
  const double ex = p.x - from.x, ey = p.y - from.y;
  along = step > 0 ? (ex * dx + ey * dy) / step : 0;
  across = step > 0 ? std::abs(ex * dy - ey * dx) / step : std::hypot(ex, ey);
}

double BallTracker::speed(const BallTrack& bt) {
  return bt.history >= 2 && bt.t[1] > bt.t[0] ? dist(bt.pos[1], bt.pos[0]) / (bt.t[1] - bt.t[0]) : 0;
}

bool BallTracker::isFast(const BallTrack& bt) const { return speed(bt) > opt_.max_robot_speed; }

int BallTracker::expectedFastBalls(double t_next, FieldMm* out, int max) const {
  int n = 0;
  for (const BallTrack& bt : tracks_)
    if (n < max && isFast(bt)) out[n++] = straightOn(bt, std::max(0.0, t_next - bt.t[1]));
  return n;
}

void BallTracker::match(BallCandidate& c) const {
  double best = std::numeric_limits<double>::max();
  for (size_t k = 0; k < tracks_.size(); ++k) {
    const BallTrack& bt = tracks_[k];
    double d = dist(c.pos, bt.predicted);
    if (d >= bt.gate) {
      // Kicked: ranked behind any candidate on the predicted course.
      const double from_last = dist(c.pos, bt.pos[1]);
      if (from_last >= bt.kick_gate) continue;
      d = bt.gate + from_last;
    }
    if (d < best) best = d, c.track = static_cast<int>(k), c.kicked = d >= bt.gate;
  }
}

bool BallTracker::isEcho(const BallCandidate& c, double t) const {
  for (const BallTrack& bt : tracks_) {
    const double v = speed(bt);
    if (!bt.confirmed || bt.t[1] != t || !(v > 0)) continue;
    // Below the ball that holds the track, unless the track has held it
    // for frames (its course is then better evidence than one blob's
    // strength) or a streak holds it (a streak's rank is a shape measure
    // that says nothing against a round blob's).
    if (!(c.rank < bt.rank || bt.streak || bt.hits >= kEstablishedHits)) continue;
    const double reach = v * kEchoTime;
    double along = 0, across = 0;
    onCourse(bt, bt.pos[1], c.pos, along, across);
    if (std::abs(along) <= reach && across <= 2 * opt_.ball_radius) return true;
  }
  return false;
}

void BallTracker::update(double t, std::vector<BallCandidate>& cands) {
  const double r = opt_.ball_radius;
  // A streak and a round blob where the ball last lay both continuing its
  // track: the ball was kicked, and the round blob is its stale picture
  // (a compressed stream's copied blocks). A ball cannot lie still and
  // move at once, and a copied picture does not blur: the streak takes
  // the track, the round blob is dropped with the echoes.
  for (auto& c : cands) {
    if (c.track < 0 || c.streak) continue;
    const FieldMm lay = tracks_[c.track].pos[1];
    if (dist(c.pos, lay) > 2 * r) continue;
    for (const auto& s : cands)
      if (s.track == c.track && s.streak && dist(s.pos, lay) > 4 * r) {
        c.track = -1, c.stale = true;
        break;
      }
  }
  // A streak where its track's course puts it is that ball in motion:
  // nothing else explains both the blur and the place. Such streaks
  // continue their tracks first, then every candidate in order.
  const auto onCourseStreak = [](const BallCandidate& c) { return c.track >= 0 && !c.kicked && c.streak; };
  for (const bool first : {true, false}) {
    for (auto& c : cands) {
      if (onCourseStreak(c) != first || c.course_only) continue;
      if (c.track < 0 || tracks_[c.track].confirmed) {
        c.track = -1;
        continue;
      }
      BallTrack& bt = tracks_[c.track];
      bt.pos[0] = bt.pos[1];
      bt.t[0] = bt.t[1];
      bt.pos[1] = c.pos;
      bt.t[1] = t;
      bt.history = 2;
      ++bt.hits;
      bt.confirmed = true;
      bt.rank = c.rank;
      bt.streak = c.streak;
    }
  }
  // What continues no track but lies on the course of a ball tracked in
  // this frame is an echo of that ball: a compressed stream's stale or
  // borrowed blocks (a B-frame copies the ball from the frames before and
  // after) show it where it lay and where it will be. One ball cannot be
  // in two places on its own course.
  cands.erase(std::remove_if(cands.begin(), cands.end(),
                             [&](const BallCandidate& c) { return c.stale || (c.track < 0 && isEcho(c, t)); }),
              cands.end());
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const BallTrack& bt) { return !bt.confirmed && t - bt.t[1] > kMaxGap; }),
                tracks_.end());
  for (const auto& c : cands) {
    if (c.track >= 0 || c.course_only || tracks_.size() >= kMaxTracks) continue;
    BallTrack bt;
    bt.pos[1] = c.pos;
    bt.t[1] = t;
    bt.history = 1;
    bt.hits = 1;
    bt.confirmed = true;
    tracks_.push_back(bt);
  }
}

}  // namespace dv

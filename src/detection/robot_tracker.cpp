#include "detection/robot_tracker.h"

#include <algorithm>
#include <cmath>

#include "detection/detector.h"

namespace dv {

RobotTrackerOptions RobotTrackerOptions::from(const DetectorOptions& o) {
  RobotTrackerOptions r;
  r.max_robot_acceleration = o.max_robot_acceleration;
  r.max_prediction_dt = o.max_prediction_dt;
  r.min_uncertainty = o.min_uncertainty;
  r.max_robot_speed = o.max_robot_speed;
  r.track_gate = o.track_gate;
  r.identity_switch_frames = o.identity_switch_frames;
  return r;
}

RobotTracker::RobotTracker(const RobotTrackerOptions& o) : opt_(o) {
  tracks_.reserve(64);
  match_.reserve(64);
  taken_.reserve(64);
}

void RobotTracker::predict(double t) {
  for (auto& tr : tracks_) {
    const double dt_last = t - tr.t[1];
    tr.predicted = tr.pos[1];
    tr.predicted_orientation = tr.orientation[1];
    if (tr.history >= 2 && tr.t[1] > tr.t[0]) {
      const double f = dt_last / (tr.t[1] - tr.t[0]);
      tr.predicted = {tr.pos[1].x + f * (tr.pos[1].x - tr.pos[0].x),
                      tr.pos[1].y + f * (tr.pos[1].y - tr.pos[0].y)};
      tr.predicted_orientation =
          wrapAngle(tr.orientation[1] + f * wrapAngle(tr.orientation[1] - tr.orientation[0]));
    }
    const double dt = std::min(std::max(dt_last, 0.0), opt_.max_prediction_dt);
    tr.uncertainty = std::max(opt_.min_uncertainty, 0.5 * opt_.max_robot_acceleration * dt * dt);
    if (tr.history < 2) tr.uncertainty = std::max(tr.uncertainty, opt_.max_robot_speed * dt);
    tr.confirmed = false;
  }
}

void RobotTracker::associate(const std::vector<Hypothesis>& robots) {
  match_.assign(robots.size(), -1);
  taken_.assign(tracks_.size(), 0);
  // Robots are in rank order: the best detections choose first.
  for (size_t r = 0; r < robots.size(); ++r) {
    int best = -1;
    double best_d = opt_.track_gate;
    for (size_t k = 0; k < tracks_.size(); ++k) {
      if (taken_[k]) continue;
      const FieldMm& p = robots[r].pose.position;
      const double d = std::hypot(p.x - tracks_[k].predicted.x, p.y - tracks_[k].predicted.y);
      if (d < best_d) best_d = d, best = static_cast<int>(k);
    }
    if (best >= 0) {
      match_[r] = best;
      taken_[best] = 1;
    }
  }
}

// A frame that follows the last one re-finds nearly every robot near its
// prediction, while a new scene (independent images played as a sequence)
// meets old tracks only by chance. A dark or occluded frame has few fresh
// robots, and those it has still meet their tracks.
bool RobotTracker::unrelated(int fresh) const {
  const int fewer = std::min(fresh, static_cast<int>(tracks_.size()));
  if (fewer < kSceneCheckMinRobots) return false;
  int associated = 0;
  for (int k : match_) associated += k >= 0;
  return 2 * associated < fewer;
}

void RobotTracker::advance(RobotTrack& tr, const Hypothesis& h, double t) {
  if (tr.history >= 1) {
    tr.pos[0] = tr.pos[1];
    tr.orientation[0] = tr.orientation[1];
    tr.t[0] = tr.t[1];
  }
  tr.pos[1] = h.pose.position;
  tr.orientation[1] = h.pose.orientation;
  tr.t[1] = t;
  tr.history = std::min(tr.history + 1, 2);
  tr.confirmed = true;
}

void RobotTracker::applyIdentity(RobotTrack& tr, Hypothesis& h, TrackHooks& hooks) const {
  // A robot missing a side blob agrees with the track when the colors it
  // shows match the track's pattern; the guessed color is no evidence.
  bool agrees = h.team == tr.team && h.id == tr.id;
  if (!agrees && h.team == tr.team && !h.fullPattern()) {
    const auto want = patternColors(tr.id);
    agrees = true;
    for (int s = 0; s < 4; ++s)
      if ((h.seen_sides >> s & 1) && h.colors[s] != want[s]) agrees = false;
  }
  if (!tr.id_certain && h.fullPattern() && !agrees) {
    // The track's id was a guess; the first full view decides.
    tr.team = h.team;
    tr.id = h.id;
    tr.pending_count = 0;
    agrees = true;
  }
  if (h.fullPattern() && h.team == tr.team && h.id == tr.id) tr.id_certain = true;
  if (agrees) {
    tr.pending_count = 0;
  } else {
    if (h.team == tr.pending_team && h.id == tr.pending_id) {
      ++tr.pending_count;
    } else {
      tr.pending_team = h.team;
      tr.pending_id = h.id;
      tr.pending_count = 1;
    }
    if (tr.pending_count >= opt_.identity_switch_frames) {
      tr.team = h.team;
      tr.id = h.id;
      tr.pending_count = 0;
    }
  }
  if (h.team != tr.team) {
    h.team = tr.team;
    hooks.refit(h);
  }
  h.id = tr.id;
}

bool RobotTracker::update(double t, std::vector<Hypothesis>& robots, TrackHooks& hooks) {
  predict(t);
  associate(robots);
  const int fresh = static_cast<int>(robots.size());
  const bool scene_changed = unrelated(fresh);
  if (scene_changed) {
    tracks_.clear();
    match_.assign(robots.size(), -1);
    taken_.clear();
  }
  for (size_t k = 0; k < tracks_.size(); ++k) {
    if (taken_[k] || !hooks.recover(tracks_[k], static_cast<int>(k), robots)) continue;
    match_.push_back(static_cast<int>(k));
    taken_[k] = 1;
  }
  for (size_t r = 0; r < robots.size(); ++r) {
    const int k = match_[r];
    if (k < 0) continue;
    if (static_cast<int>(r) < fresh) applyIdentity(tracks_[k], robots[r], hooks);
    if (tracks_[k].id_certain) robots[r].id_known = true;
    advance(tracks_[k], robots[r], t);
  }
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [](const RobotTrack& tr) { return !tr.confirmed; }),
                tracks_.end());
  for (int r = 0; r < fresh; ++r) {
    if (match_[r] >= 0) continue;
    RobotTrack tr;
    tr.team = robots[r].team;
    tr.id = robots[r].id;
    tr.id_certain = robots[r].fullPattern();
    advance(tr, robots[r], t);
    tracks_.push_back(tr);
  }
  return scene_changed;
}

}  // namespace dv

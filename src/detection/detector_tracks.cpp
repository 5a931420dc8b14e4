#include "detection/detector_impl.h"

namespace dv {

void Detector::Impl::predictTracks(double t) {
  for (auto& tr : tracks) {
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
    const double dt = std::min(std::max(dt_last, 0.0), opt.max_prediction_dt);
    tr.uncertainty = std::max(opt.min_uncertainty, 0.5 * opt.max_robot_acceleration * dt * dt);
    if (tr.history < 2) tr.uncertainty = std::max(tr.uncertainty, opt.max_robot_speed * dt);
    tr.confirmed = false;
  }
}

void Detector::Impl::associateTracks() {
  track_match.assign(robots.size(), -1);
  track_taken.assign(tracks.size(), 0);
  // Robots are in rank order: the best detections choose first.
  for (size_t r = 0; r < robots.size(); ++r) {
    int best = -1;
    double best_d = opt.track_gate;
    for (size_t k = 0; k < tracks.size(); ++k) {
      if (track_taken[k]) continue;
      const double d = dist(robots[r].pose.position, tracks[k].predicted);
      if (d < best_d) best_d = d, best = static_cast<int>(k);
    }
    if (best >= 0) {
      track_match[r] = best;
      track_taken[best] = 1;
    }
  }
}

void Detector::Impl::recoverTrack(int k) {
  const RobotTrack& tr = tracks[k];
  const int team = tr.team == Team::Yellow ? 0 : 1;
  const double h = teamHeight(tr.team);
  const auto colors = patternColors(tr.id);
  int cand[kPatternSlots][kMaxSlotCandidates];
  int ncand[kPatternSlots] = {0, 0, 0, 0, 0};
  double cdist[kPatternSlots][kMaxSlotCandidates];
  for (int s = 0; s < kPatternSlots; ++s) {
    const FieldMm e = slotPosition(tr.predicted, tr.predicted_orientation, s);
    FieldMm e_ref;
    if (!alongRay(e, h, ref_height, e_ref)) continue;
    const auto& hits = index.within(e_ref, tr.uncertainty * 1.2 + 2);
    for (const auto& hit : hits) {
      const int i = static_cast<int>(hit.first);
      const FrameBlob& b = blobs[i];
      if (!b.valid || b.robot >= 0) continue;
      const double d = dist(b.at_team[team], e);
      if (d > tr.uncertainty) continue;
      if (s == 0) {
        if (nearestOf(b.color, kYellow, kBlue) != (team == 0 ? kYellow : kBlue)) continue;
      } else {
        const int want = colors[s - 1] == MarkerColor::Green ? kGreen : kPink;
        if (nearestOf(b.color, kGreen, kPink) != want) continue;
      }
      // keep the nearest few
      int pos = ncand[s];
      if (pos == kMaxSlotCandidates) {
        if (d >= cdist[s][pos - 1]) continue;
        --pos;
      } else {
        ++ncand[s];
      }
      while (pos > 0 && cdist[s][pos - 1] > d) {
        cand[s][pos] = cand[s][pos - 1];
        cdist[s][pos] = cdist[s][pos - 1];
        --pos;
      }
      cand[s][pos] = i;
      cdist[s][pos] = d;
    }
  }
  // Enumerate: each slot takes one of its candidates or none.
  Hypothesis best;
  best.rank = -1;
  int choice[kPatternSlots];
  for (int s = 0; s < kPatternSlots; ++s) choice[s] = -1;
  auto evaluate = [&]() {
    Hypothesis hyp;
    FieldMm pts[kPatternSlots];
    for (int s = 0; s < kPatternSlots; ++s) {
      if (choice[s] < 0) continue;
      const int b = cand[s][choice[s]];
      for (int q = 0; q < hyp.n; ++q)
        if (hyp.blob[q] == b) return;  // a blob fills one slot only
      hyp.blob[hyp.n] = b;
      hyp.slot[hyp.n] = s;
      pts[hyp.n] = blobs[b].at_team[team];
      ++hyp.n;
    }
    if (hyp.n < 2) return;
    hyp.pose = fitPattern(pts, hyp.slot, hyp.n, opt.score_scale);
    if (hyp.pose.score < opt.min_robot_score) return;
    hyp.rank = hyp.pose.score * (0.5 + 0.1 * hyp.n);
    if (hyp.rank > best.rank) best = hyp;
  };
  auto recurse = [&](auto&& self, int s) -> void {
    if (s == kPatternSlots) return evaluate();
    for (int c = -1; c < ncand[s]; ++c) {
      choice[s] = c;
      self(self, s + 1);
    }
    choice[s] = -1;
  };
  recurse(recurse, 0);
  if (best.rank < 0 || overlapsAccepted(best.pose)) return;
  best.team = tr.team;
  best.id = tr.id;
  best.confidence = best.pose.score * best.n / 5.0;
  best.track = k;
  for (int i = 0; i < best.n; ++i) blobs[best.blob[i]].robot = static_cast<int>(robots.size());
  robots.push_back(best);
  track_match.push_back(k);
  track_taken[k] = 1;
}

void Detector::Impl::updateTrack(RobotTrack& tr, const Hypothesis& h, double t) {
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

void Detector::Impl::applyIdentity(RobotTrack& tr, Hypothesis& h) {
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
    if (tr.pending_count >= opt.identity_switch_frames) {
      tr.team = h.team;
      tr.id = h.id;
      tr.pending_count = 0;
    }
  }
  if (h.team != tr.team) {
    h.team = tr.team;
    refit(h);
  }
  h.id = tr.id;
}

bool Detector::Impl::unrelatedToTracks() const {
  const int fresh = static_cast<int>(robots.size()), known = static_cast<int>(tracks.size());
  const int fewer = std::min(fresh, known);
  if (fewer < kSceneCheckMinRobots) return false;
  int associated = 0;
  for (int k : track_match) associated += k >= 0;
  return 2 * associated < fewer;
}

void Detector::Impl::track(double t) {
  predictTracks(t);
  associateTracks();
  if (unrelatedToTracks()) {
    tracks.clear();
    ball_tracks.clear();
    track_match.assign(robots.size(), -1);
    track_taken.clear();
    new_scene = true;
  }
  const size_t fresh = robots.size();
  for (size_t k = 0; k < tracks.size(); ++k)
    if (!track_taken[k]) recoverTrack(static_cast<int>(k));
  for (size_t r = 0; r < robots.size(); ++r) {
    const int k = track_match[r];
    if (k < 0) continue;
    if (r < fresh) applyIdentity(tracks[k], robots[r]);
    if (tracks[k].id_certain) robots[r].id_known = true;
    updateTrack(tracks[k], robots[r], t);
  }
  // Drop tracks this frame did not confirm, then start new ones.
  tracks.erase(std::remove_if(tracks.begin(), tracks.end(),
                              [](const RobotTrack& tr) { return !tr.confirmed; }),
               tracks.end());
  for (size_t r = 0; r < fresh; ++r) {
    if (track_match[r] >= 0) continue;
    RobotTrack tr;
    tr.team = robots[r].team;
    tr.id = robots[r].id;
    tr.id_certain = robots[r].fullPattern();
    updateTrack(tr, robots[r], t);
    tracks.push_back(tr);
  }
}

}  // namespace dv

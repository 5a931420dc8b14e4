// Blob-level recovery of tracks (the detector's part of tracking); the
// tracks themselves and identity hysteresis are robot_tracker.cpp's.
#include "detection/detector_impl.h"

namespace dv {
void Detector::Impl::track(double t) {
  struct Hooks final : TrackHooks {
    explicit Hooks(Impl& d) : d(d) {}
    bool recover(const RobotTrack& track, int index, std::vector<Hypothesis>& out) override {
      return d.recoverTrack(track, index, out);
    }
    void refit(Hypothesis& h) override { d.refit(h); }
    Impl& d;
  } hooks(*this);
  if (tracker.update(t, robots, hooks)) {
    ball_tracker.clear();
    fast_streaks.clear();
    new_scene = true;
  }
}

bool Detector::Impl::recoverTrack(const RobotTrack& tr, int k, std::vector<Hypothesis>& out) {
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
  if (best.rank < 0 || overlapsAccepted(best.pose)) return false;
  best.team = tr.team;
  best.id = tr.id;
  best.confidence = best.pose.score * best.n / 5.0;
  best.track = k;
  for (int i = 0; i < best.n; ++i) blobs[best.blob[i]].robot = static_cast<int>(out.size());
  out.push_back(best);
  return true;
}

}  // namespace dv

#include "detection/detector_impl.h"
#include "detection/ring_orientation.h"
#include "detection/seen_color.h"

namespace dv {

void Detector::Impl::findHypotheses() {
  hyps.clear();
  const int nb = n_strong;
  const bool weak_on = !weak_index.points().empty();
  std::array<int, 64> nbr;
  std::array<double, 64> ang;
  std::array<double, 64> dev;
  for (int c = 0; c < nb; ++c) {
    if (!blobs[c].valid || blobs[c].streak) continue;
    const FieldMm cp = blobs[c].at_ref;
    const auto& hits = index.within(cp, opt.side_search_radius);
    int k = 0;
    for (const auto& h : hits) {
      const int i = static_cast<int>(h.first);
      if (i == c || h.second < sq(kMinSideDistance)) continue;
      // A peak much darker than the center is the robot top's (chroma
      // ringing around the dots after JPEG), never a marker.
      if (brightness(i) < kTopBrightness * brightness(c)) continue;
      if (k == static_cast<int>(nbr.size())) break;
      nbr[k] = i;
      dev[k] = std::abs(std::sqrt(h.second) - RobotPatternGeometry::kSideBlobDistance);
      ++k;
    }
    if (!weak_on && k < 2) continue;
    if (k > kMaxNeighbors) {  // keep the ones nearest to the side blob ring
      for (int a = 0; a < kMaxNeighbors; ++a) {
        int best = a;
        for (int b = a + 1; b < k; ++b)
          if (dev[b] < dev[best]) best = b;
        std::swap(nbr[a], nbr[best]);
        std::swap(dev[a], dev[best]);
      }
      k = kMaxNeighbors;
    }
    for (int a = 0; a < k; ++a) {
      const FieldMm q = blobs[nbr[a]].at_ref;
      ang[a] = std::atan2(q.y - cp.y, q.x - cp.x);
    }
    // Sort by angle (insertion sort, k <= 10).
    for (int a = 1; a < k; ++a)
      for (int b = a; b > 0 && ang[b] < ang[b - 1]; --b) {
        std::swap(ang[b], ang[b - 1]);
        std::swap(nbr[b], nbr[b - 1]);
      }
    const FitTolerance tol = fitToleranceAt(cp);
    Hypothesis best;
    best.rank = -1;
    // Side blobs in increasing angle map to slots in increasing angle, up
    // to a cyclic shift (which blob is front-left).
    auto consider = [&](const int* pick, int m, const int* slots_sorted) {
      Hypothesis h;
      h.n = m + 1;
      h.blob[0] = c;
      h.slot[0] = 0;
      FieldMm pts[kPatternSlots];
      pts[0] = cp;
      for (int r = 0; r < m; ++r) {
        for (int q = 0; q < m; ++q) {
          h.blob[q + 1] = nbr[pick[q]];
          h.slot[q + 1] = slots_sorted[(q + r) % m];
          pts[q + 1] = blobs[nbr[pick[q]]].at_ref;
        }
        h.pose = fitPattern(pts, h.slot, h.n, tol);
        h.rank = h.pose.score * (m == 4 ? 1.0 : kFourBlobPenalty);
        if (h.pose.score >= opt.min_robot_score && h.rank > best.rank) best = h;
      }
    };
    int pick[4];
    static constexpr int kAllSlots[4] = {1, 2, 3, 4};
    for (pick[0] = 0; pick[0] < k; ++pick[0])
      for (pick[1] = pick[0] + 1; pick[1] < k; ++pick[1])
        for (pick[2] = pick[1] + 1; pick[2] < k; ++pick[2])
          for (pick[3] = pick[2] + 1; pick[3] < k; ++pick[3]) consider(pick, 4, kAllSlots);
    // Three side blobs can only win when no full pattern ranks above
    // their best possible rank.
    if (opt.min_side_blobs <= 3 && best.rank < kFourBlobPenalty) {
      for (pick[0] = 0; pick[0] < k; ++pick[0])
        for (pick[1] = pick[0] + 1; pick[1] < k; ++pick[1])
          for (pick[2] = pick[1] + 1; pick[2] < k; ++pick[2])
            for (int missing = 1; missing <= 4; ++missing) {
              int slots[3], s = 0;
              for (int q = 1; q <= 4; ++q)
                if (q != missing) slots[s++] = q;
              consider(pick, 3, slots);
            }
    }
    if (weak_on && !(best.rank > 0 && best.n == kPatternSlots)) completeWithWeak(c, nbr.data(), k, best);
    if (best.rank <= 0) completeFromTwoSides(c, nbr.data(), k, best);
    if (best.rank > 0) hyps.push_back(best);
  }
}

FitTolerance Detector::Impl::fitToleranceAt(const FieldMm& p) const {
  FitTolerance t{opt.score_scale};
  if (!stretched_view) return t;
  double dir[2];
  const double s = viewStretch(camera, p, ref_height, dir);
  if (s >= kMinStretch) t.stretch = s, t.along_x = dir[0], t.along_y = -dir[1];
  return t;
}

bool Detector::Impl::seesStretchedField() const {
  const auto& c = camera.calibration();
  constexpr double kStep = 100;
  for (double y = ball_area.y_min; y <= ball_area.y_max; y += kStep)
    for (double x = ball_area.x_min; x <= ball_area.x_max; x += kStep) {
      const auto px = camera.fieldToImage({x, y, ref_height});
      if (!px || px->u < 0 || px->v < 0 || px->u > c.image_width - 1 || px->v > c.image_height - 1) continue;
      double dir[2];
      if (viewStretch(camera, {x, y}, ref_height, dir) >= kMinStretch) return true;
    }
  return false;
}

void Detector::Impl::completeWithWeak(int c, const int* nbr, int k, Hypothesis& best) {
  const FieldMm cp = blobs[c].at_ref;
  if (weak_index.within(cp, opt.side_search_radius).empty()) return;
  const FitTolerance tol = fitToleranceAt(cp);
  // The pattern of n blobs (slots given) at `pose`, with weak peaks in its
  // missing slots; at least `min_n` blobs in all, or (`marker_ok`) one
  // fewer where the slot left shows a marker in the frame.
  auto tryPattern = [&](const int* blob, const int* slot, int n, const PatternPose& pose, int min_n,
                        bool marker_ok = false) {
    unsigned filled = 0;
    for (int i = 0; i < n; ++i) filled |= 1u << slot[i];
    int found[kPatternSlots];
    double error[kPatternSlots];
    FitTolerance weak_tol = tol;
    weak_tol.mm = opt.weak_side_tolerance;
    int n_weak = findWeakSlots(pose, filled, weak_index, weak_tol, found, error);
    // A weak peak much darker than the center is the robot top's (the dark
    // rim around a pale dot), not a marker.
    for (int s = 1; s < kPatternSlots; ++s)
      if (found[s] >= 0 && brightness(n_strong + found[s]) < kTopBrightness * brightness(c)) found[s] = -1, --n_weak;
    if (n_weak == 0 || n + n_weak < min_n - marker_ok) return;
    // A diagonal pair fits both diagonals, and a marker of one placement
    // lies near a slot of the other: where the ring shows the robot's
    // orientation, the placement must agree with it.
    if (n == 3 && std::abs(slot[1] - slot[2]) == 2 && !agreesWithRing(c, pose)) return;
    if (n + n_weak < min_n)
      for (int s = 1; s < kPatternSlots; ++s)
        if (!(filled >> s & 1u) && found[s] < 0 && !slotShowsMarker(pose, s, c)) return;
    Hypothesis h;
    h.n = 0;
    FieldMm pts[kPatternSlots];
    for (int i = 0; i < n; ++i) h.blob[h.n] = blob[i], h.slot[h.n] = slot[i], pts[h.n++] = blobs[blob[i]].at_ref;
    for (int s = 0; s < kPatternSlots; ++s) {
      if (found[s] < 0) continue;
      const int b = n_strong + found[s];
      h.blob[h.n] = b, h.slot[h.n] = s, pts[h.n++] = blobs[b].at_ref;
    }
    h.pose = fitPattern(pts, h.slot, h.n, tol);
    if (h.pose.score < opt.min_weak_fit) return;
    int all_weak = n_weak;
    for (int i = 0; i < n; ++i) all_weak += blobs[blob[i]].weak;
    h.rank = h.pose.score * (h.n == kPatternSlots ? 1.0 : kFourBlobPenalty) * (1 - kWeakSideRankStep * all_weak);
    if (h.rank > best.rank) best = h;
  };
  auto onRing = [&](const FieldMm& p) {
    return std::abs(dist(p, cp) - RobotPatternGeometry::kSideBlobDistance) <= kWeakPairRingTolerance;
  };
  if (best.rank > 0 && best.n == kPatternSlots - 1)
    tryPattern(best.blob, best.slot, best.n, best.pose, kPatternSlots);
  if (best.rank > 0 && best.n == kPatternSlots) return;
  // Two side blobs: on the ring, as far apart in angle as two slots.
  bool side_pair = false;
  forSideBlobPairs(c, nbr, k, [&](const int* blob, const int* slot, const PatternPose& pose) {
    side_pair = true;
    tryPattern(blob, slot, 3, pose, kPatternSlots - 1);
  });
  if (best.rank > 0) return;
  // One side blob: each slot it may be, the other three all weak.
  for (int a = 0; a < k; ++a) {
    const FieldMm pa = blobs[nbr[a]].at_ref;
    if (!onRing(pa)) continue;
    for (int sa = 1; sa < kPatternSlots; ++sa) {
      const int blob[2] = {c, nbr[a]}, slot[2] = {0, sa};
      const FieldMm pts[2] = {cp, pa};
      tryPattern(blob, slot, 2, fitPattern(pts, slot, 2, tol), kPatternSlots);
    }
  }
  if (best.rank > 0 || side_pair) return;
  // Weak peaks for side blobs too, where no two side blobs fit the pattern
  // (those set the pose, and weak peaks off its slots are no markers): a
  // center whose markers peaked below the threshold, all or all but one (a
  // desaturated, cast frame at low resolution: chroma contrast falls for
  // the small side dots first). Any two of its side peaks, strong or weak,
  // on the ring give the pose, and weak peaks must then fill the other
  // slots, all but one that shows a marker in the frame. (Three side
  // peaks alone let noise make robots: precision 0.96 on the dark, noisy
  // preset at 1224 x 1024, and yellow robots where only blue ones stood.)
  std::array<int, 64> sides;
  const int m = sidePeaks(c, nbr, k, sides);
  if (m < kPatternSlots - 2) return;
  forSideBlobPairs(c, sides.data(), m, [&](const int* blob, const int* slot, const PatternPose& pose) {
    tryPattern(blob, slot, 3, pose, kPatternSlots, /*marker_ok=*/true);
  });
}

int Detector::Impl::sidePeaks(int c, const int* nbr, int k, std::array<int, 64>& out) {
  int m = 0;
  for (int i = 0; i < k && m < static_cast<int>(out.size()); ++i) out[m++] = nbr[i];
  for (const auto& hit : weak_index.within(blobs[c].at_ref, opt.side_search_radius)) {
    if (m == static_cast<int>(out.size())) break;
    const int w = n_strong + static_cast<int>(hit.first);
    if (hit.second >= sq(kMinSideDistance) && brightness(w) >= kTopBrightness * brightness(c)) out[m++] = w;
  }
  return m;
}

bool Detector::Impl::slotOutOfView(const PatternPose& pose, int slot) const {
  const FieldMm p = slotPosition(pose.position, pose.orientation, slot);
  const auto& c = camera.calibration();
  const double w = c.image_width, h = c.image_height;
  constexpr int kRim = 8;
  for (int i = 0; i < kRim; ++i) {
    const double a = 2 * kPi * i / kRim;
    const auto px = camera.fieldToImage({p.x + kEdgeBlobRadius * std::cos(a),
                                         p.y + kEdgeBlobRadius * std::sin(a), ref_height});
    if (!px || px->u < -0.5 || px->v < -0.5 || px->u > w - 0.5 || px->v > h - 0.5) return true;
  }
  return false;
}

bool Detector::Impl::slotShowsMarker(const PatternPose& pose, int slot, int c) const {
  if (!opt.probe_missing_sides || !frame_view.image) return false;
  const FieldMm p = slotPosition(pose.position, pose.orientation, slot);
  const SeenColor seen = seenDiscColor(frame_view, camera, {p.x, p.y, ref_height}, opt.probe_radius);
  if (seen.share < 1) return false;
  const float bright = seen.rgb[0] + seen.rgb[1] + seen.rgb[2];
  if (bright < kMarkerBrightness * brightness(c)) return false;
  const double out = kCarpetProbeDistance / RobotPatternGeometry::kSideBlobDistance;
  const FieldPoint beyond{pose.position.x + out * (p.x - pose.position.x),
                          pose.position.y + out * (p.y - pose.position.y), 0};
  const SeenColor carpet = seenDiscColor(frame_view, camera, beyond, opt.probe_radius);
  const ColorVec carpet_color = colorFeature(carpet.rgb[0], carpet.rgb[1], carpet.rgb[2]);
  const bool is_carpet = carpet.share > 0 && colorDistance(carpet_color, classes[kField].color) <
                                                 colorDistance(carpet_color, classes[kWhite].color);
  if (is_carpet && bright < kOverCarpet * (carpet.rgb[0] + carpet.rgb[1] + carpet.rgb[2])) return false;
  return weakSideColor(colorFeature(seen.rgb[0], seen.rgb[1], seen.rgb[2]), classes[kGreen].color,
                       classes[kPink].color, static_cast<float>(opt.weak_color_margin)) >= 0;
}

void Detector::Impl::completeFromTwoSides(int c, const int* nbr, int k, Hypothesis& best) {
  // Reading the frame costs: only for a center that looks like a team
  // color rather than a side color (a side blob is a center candidate too).
  auto nearer = [&](int a, int b) {
    return std::min(colorDistance(blobs[c].color, classes[a].color), colorDistance(blobs[c].color, classes[b].color));
  };
  // A center clipped in two channels has no reliable color: its markers
  // decide.
  const bool center_like =
      nearer(kYellow, kBlue) < nearer(kGreen, kPink) || ClippedColor(blobs[c].rgb).saturated();
  // Whether the slots of `pose` other than slot[1], slot[2] are out of
  // view or show markers; `by_marker`: at least one shows a marker.
  auto othersShown = [&](const int* blob, const int* slot, const PatternPose& pose, int n_weak, bool& by_marker) {
    by_marker = false;
    for (int s = 1; s < kPatternSlots; ++s) {
      if (s == slot[1] || s == slot[2] || (n_weak == 0 && slotOutOfView(pose, s))) continue;
      if (!center_like || !slotShowsMarker(pose, s, blob[0])) return false;
      by_marker = true;
    }
    return true;
  };
  const FitTolerance tol = fitToleranceAt(blobs[c].at_ref);
  auto take = [&](const int* blob, const int* slot, const PatternPose& pose) {
    const int n_weak = blobs[blob[1]].weak + blobs[blob[2]].weak;
    const double rank = pose.score * kFourBlobPenalty * kEdgeRankFactor * (1 - kWeakSideRankStep * n_weak);
    if (rank <= best.rank) return;
    bool by_marker;
    if (!othersShown(blob, slot, pose, n_weak, by_marker)) return;
    if (by_marker && (slot[1] - slot[2]) % 2 == 0) {
      const int a = slot[1] % 4 + 1, b = slot[2] % 4 + 1;  // the other diagonal
      for (const auto& alt : {std::array<int, 3>{0, a, b}, std::array<int, 3>{0, b, a}}) {
        const FieldMm pts[3] = {blobs[blob[0]].at_ref, blobs[blob[1]].at_ref, blobs[blob[2]].at_ref};
        const PatternPose other = fitPattern(pts, alt.data(), 3, tol);
        bool unused;
        if (other.score >= opt.min_weak_fit && othersShown(blob, alt.data(), other, n_weak, unused)) return;
      }
    }
    Hypothesis h;
    h.n = 3;
    for (int i = 0; i < 3; ++i) h.blob[i] = blob[i], h.slot[i] = slot[i];
    h.pose = pose;
    h.rank = rank;
    best = h;
  };
  forSideBlobPairs(c, nbr, k, take);
  if (best.rank > 0) return;
  // A weak peak stands only beside a side blob here: none, nothing to pair.
  if (k > 0 && !weak_index.points().empty()) {
    std::array<int, 64> mixed;
    const int m = sidePeaks(c, nbr, k, mixed);
    if (m > k)
      forSideBlobPairs(c, mixed.data(), m, [&](const int* blob, const int* slot, const PatternPose& pose) {
        if (blobs[blob[1]].weak != blobs[blob[2]].weak) take(blob, slot, pose);
      });
  }
  if (best.rank <= 0 && center_like) completeFromOneSide(c, nbr, k, best);
  if (best.rank <= 0 && center_like) completeFromCenter(c, best);
}

bool Detector::Impl::agreesWithRing(int c, const PatternPose& pose) const {
  if (!opt.probe_missing_sides) return true;
  const FieldMm cp = blobs[c].at_ref;
  const auto o = ringOrientation(frame_view, camera, {cp.x, cp.y, ref_height}, kMarkerBrightness * brightness(c));
  return !o || std::abs(wrapAngle(pose.orientation - *o)) <= kRingAgreement;
}

void Detector::Impl::completeFromCenter(int c, Hypothesis& best) {
  if (!opt.probe_missing_sides || !frame_view.image) return;
  // Not the ball: a center nearer to the orange class than to both teams'
  // is left to the ball policy (a clipped center's color says too little).
  const ClippedColor seen(blobs[c].rgb);
  if (!seen.saturated() && seen.distance(classes[kOrange].color) <
                               std::min(seen.distance(classes[kYellow].color), seen.distance(classes[kBlue].color)))
    return;
  const FieldMm cp = blobs[c].at_ref;
  const auto orientation = ringOrientation(frame_view, camera, {cp.x, cp.y, ref_height},
                                           kMarkerBrightness * brightness(c));
  if (!orientation) return;
  PatternPose pose;
  pose.position = cp;
  pose.orientation = *orientation;
  pose.score = 1;
  for (int s = 1; s < kPatternSlots; ++s)
    if (slotOutOfView(pose, s) || !slotShowsMarker(pose, s, c)) return;
  const double rank = kFourBlobPenalty * kEdgeRankFactor * kOneSideRankFactor * kOneSideRankFactor;
  if (rank <= best.rank) return;
  Hypothesis h;
  h.n = 1;
  h.blob[0] = c;
  h.slot[0] = 0;
  h.pose = pose;
  h.rank = rank;
  best = h;
}

void Detector::Impl::completeFromOneSide(int c, const int* nbr, int k, Hypothesis& best) {
  const FieldMm cp = blobs[c].at_ref;
  const FitTolerance tol = fitToleranceAt(cp);
  Hypothesis found;
  int n_found = 0;
  for (int a = 0; a < k; ++a) {
    const FieldMm pa = blobs[nbr[a]].at_ref;
    if (std::abs(dist(pa, cp) - RobotPatternGeometry::kSideBlobDistance) > kWeakPairRingTolerance) continue;
    for (int sa = 1; sa < kPatternSlots; ++sa) {
      const int blob[2] = {c, nbr[a]}, slot[2] = {0, sa};
      const FieldMm pts[2] = {cp, pa};
      const PatternPose pose = fitPattern(pts, slot, 2, tol);
      if (pose.score < opt.min_weak_fit) continue;
      bool shown = true;
      for (int s = 1; s < kPatternSlots && shown; ++s)
        if (s != sa) shown = !slotOutOfView(pose, s) && slotShowsMarker(pose, s, c);
      if (!shown) continue;
      ++n_found;
      found.n = 2;
      for (int i = 0; i < 2; ++i) found.blob[i] = blob[i], found.slot[i] = slot[i];
      found.pose = pose;
      found.rank = pose.score * kFourBlobPenalty * kEdgeRankFactor * kOneSideRankFactor;
    }
  }
  if (n_found == 1 && found.rank > best.rank) best = found;
}

bool Detector::Impl::overlapsAccepted(const PatternPose& pose, const Hypothesis* skip) const {
  for (const auto& r : robots) {
    if (&r == skip) continue;
    if (robotTopsOverlap(pose.position, pose.orientation, r.pose.position, r.pose.orientation))
      return true;
  }
  return false;
}

void Detector::Impl::selectRobots() {
  robots.clear();
  std::sort(hyps.begin(), hyps.end(),
            [](const Hypothesis& a, const Hypothesis& b) { return a.rank > b.rank; });
  for (auto& b : blobs) b.robot = -1;
  for (const auto& h : hyps) {
    if (blobs[h.blob[0]].implausible_center) continue;
    bool free = true;
    for (int i = 0; i < h.n && free; ++i) free = blobs[h.blob[i]].robot < 0;
    if (!free || overlapsAccepted(h.pose)) continue;
    for (int i = 0; i < h.n; ++i) blobs[h.blob[i]].robot = static_cast<int>(robots.size());
    robots.push_back(h);
    robots.back().confidence = h.rank;
  }
}

}  // namespace dv

// Robots whose center made no blob (detector_impl.h,
// robotsAroundUnpeakedCenters): the pattern's side blobs alone give the
// pose, the frame tells the center's color.
#include "detection/detector_impl.h"

namespace dv {
namespace {

// How many free side blobs one blob may pair with (the pattern's other
// three, with room for clutter).
constexpr int kMaxPartners = 16;
// Such a robot's confidence: its pose's fit, a share lower than a robot
// whose center peaked (the rank a pattern completed from the frame takes).
constexpr double kUnpeakedCenterRankFactor = 0.8;
// A rank factor for a missing side blob, as the hypothesis search's.
constexpr double kThreeSidePenalty = 0.5;

// Whether `seen` is nearer to class a or b of `colors` than to every other
// class but orange; `nearer_a`: a is the nearer of the two.
bool nearerToEither(const ClippedColor& seen, const ColorVec* colors, int a, int b, bool* nearer_a) {
  const float d_a = seen.distance(colors[a]), d_b = seen.distance(colors[b]);
  const float d = std::min(d_a, d_b);
  for (int k : {kYellow, kBlue, kGreen, kPink, kField, kWhite})
    if (k != a && k != b && !(d < seen.distance(colors[k]))) return false;
  if (nearer_a) *nearer_a = d_a <= d_b;
  return true;
}

}  // namespace

bool Detector::Impl::teamColored(const ClippedColor& seen, Team* team) const {
  bool yellow = false;
  if (!nearerToEither(seen, frame_color, kYellow, kBlue, &yellow)) return false;
  if (team) *team = yellow ? Team::Yellow : Team::Blue;
  return true;
}

bool Detector::Impl::sideColored(const ClippedColor& seen) const {
  return nearerToEither(seen, frame_color, kGreen, kPink, nullptr);
}

bool Detector::Impl::teamOfFullPattern(const ClippedColor& seen, Team* team) const {
  // Nearer to one team than the other means something only where both
  // are this frame's colors, not a class's reference.
  if (!frame_seen[kYellow] || !frame_seen[kBlue]) return teamColored(seen, team);
  const float d_yellow = seen.distance(frame_color[kYellow]), d_blue = seen.distance(frame_color[kBlue]);
  if (!(std::min(d_yellow, d_blue) < seen.distance(frame_color[kField]))) return false;
  *team = d_yellow <= d_blue ? Team::Yellow : Team::Blue;
  if (seen.white()) *team = team_brightness[0] >= team_brightness[1] ? Team::Yellow : Team::Blue;
  return true;
}

void Detector::Impl::learnUnseenTeam() {
  if (frame_seen[kYellow] == frame_seen[kBlue]) return;
  const int seen = frame_seen[kYellow] ? kYellow : kBlue, unseen = kYellow + kBlue - seen;
  const int seen_label = seen == kYellow ? 0 : 1;
  const size_t n_robots = robots.size(), n_blobs = blobs.size();
  probing_unseen_team = true;
  robotsAroundUnpeakedCenters();
  probing_unseen_team = false;
  const bool probed = robots.size() > n_robots && neutral.valid;
  // The split is learned from the unclipped centers where the seen team
  // shows some; where every one of its centers clipped (an amber team in
  // a sun-lit, over-exposed frame), the probed ones alone would be all
  // the samples: then from every center, as the first split was.
  bool seen_unclipped = false;
  for (size_t i = 0; i < n_robots; ++i)
    seen_unclipped = seen_unclipped || !centerSeen(blobs[robots[i].blob[0]]).saturated();
  TwoMeansResult r;
  if (probed) r = clusterCenters(seen_unclipped);
  // (Most of the seen team's: a first-pass robot of two dots may be
  // anything.)
  bool whole = probed && r.separated;
  int seen_split[2] = {0, 0};
  for (size_t i = 0; i < n_robots && whole; ++i) ++seen_split[center_labels[i]];
  whole = whole && seen_split[seen_label] > seen_split[1 - seen_label];
  for (size_t i = n_robots; i < robots.size() && whole; ++i) whole = center_labels[i] != seen_label;
  // The unseen team's color is its probed centers' alone: a first-pass
  // robot that joined their cluster may be anything (extreme #470: a
  // brown and a dark green center pulled the gray sky-blue centers' mean
  // below the lines' blue over green).
  if (whole) {
    samples.clear();
    sample_rgb.clear();
    for (size_t i = n_robots; i < robots.size(); ++i) addSample(centerRgb(blobs[robots[i].blob[0]]));
    labels.resize(samples.size());
    const ColorVec teams[2] = {classes[kYellow].color, classes[kBlue].color};
    r = oneClass(samples.data(), static_cast<int>(samples.size()), teams, 1 - seen_label, labels.data());
  }
  for (size_t i = n_robots; i < robots.size(); ++i)
    for (int b = 0; b < robots[i].n; ++b) blobs[robots[i].blob[b]].robot = -1;
  robots.resize(n_robots);
  blobs.resize(n_blobs);
  if (!whole) return;
  // Blue lies above the lines' blue over green, yellow below, under any
  // cast. Where every center of the seen team clipped, the lines, the
  // brightest paint, clipped too and tell no cast (extreme #640, lines
  // (229, 237, 222) by gray sky-blue centers at 0.93): the seen team's
  // color is the reference then, on the other side under any cast.
  auto blueOverGreen = [](const float* c) { return c[2] / std::max(c[1], 1e-3f); };
  const float* reference = seen_unclipped ? neutral.rgb : frame_color[seen].c;
  if ((blueOverGreen(r.mean[1 - seen_label].c) > blueOverGreen(reference)) != (unseen == kBlue)) return;
  learnClassFrom(unseen, r, 1 - seen_label);
}

int Detector::Impl::robotsAroundUnpeakedCenters() {
  if (!frame_view.image || !opt.probe_missing_sides) return 0;
  auto free = [&](int i) {
    const FrameBlob& b = blobs[i];
    return b.valid && !b.streak && !b.weak && b.robot < 0;
  };
  // A dot that peaked only in the fast-ball pass (washed out, it scored
  // below the blob threshold as a disc; its chroma run still peaked as a
  // streak) may be a side: extreme #176, a pink of (240, 184, 186) beside a
  // green and a pink blob. A streak is no part of a hypothesis of the
  // first search, but here two free side blobs and the frame's center
  // vouch for the slot it fills; a ball lies no nearer a robot's center
  // than its top's radius and fills no slot.
  auto streakDot = [&](int i) {
    const FrameBlob& b = blobs[i];
    return b.valid && b.streak && b.robot < 0;
  };
  // (Streaks are kept out of the index: listed once here.)
  streak_blobs.clear();
  for (int b = 0; b < n_strong; ++b)
    if (blobs[b].valid && blobs[b].streak) streak_blobs.push_back(b);
  // Two side slots lie this far apart on the robot top at most.
  const double reach = 2 * RobotPatternGeometry::kSideBlobDistance + opt.weak_side_tolerance;
  std::array<int, kMaxPartners> partner;
  int added = 0;
  for (int a = 0; a < n_strong; ++a) {
    if (!free(a)) continue;
    int k = 0;
    for (const auto& hit : index.within(blobs[a].at_ref, reach)) {
      const int b = static_cast<int>(hit.first);
      if (b != a && k < kMaxPartners && free(b)) partner[k++] = b;
    }
    for (const int b : streak_blobs)
      if (k < kMaxPartners && streakDot(b) && detector_detail::dist(blobs[a].at_ref, blobs[b].at_ref) < reach)
        partner[k++] = b;
    // The best pattern blob a takes part in (four sides before three).
    Hypothesis best;
    float best_rgb[3] = {0, 0, 0};
    for (int j = 0; j < k; ++j) {
      const int b = partner[j];
      const double d_ab = detector_detail::dist(blobs[a].at_ref, blobs[b].at_ref);
      for (int sa = 1; sa < kPatternSlots; ++sa)
        for (int sb = sa + 1; sb < kPatternSlots; ++sb) {
          const FieldMm oa = patternOffset(sa), ob = patternOffset(sb);
          if (std::abs(d_ab - detector_detail::dist(oa, ob)) > opt.weak_side_tolerance) continue;
          for (int swap = 0; swap < 2; ++swap) {
            Hypothesis h;
            float rgb[3];
            if (patternAroundSides(a, swap ? sb : sa, b, swap ? sa : sb, partner.data(), k, h, rgb) &&
                h.rank > best.rank)
              best = h, std::copy(rgb, rgb + 3, best_rgb);
          }
        }
    }
    if (best.rank <= 0) continue;
    if (best.blob[0] < 0) {
      const FrameBlob center = centerBlobAt(best.pose.position, best_rgb);
      // The blob list's reserve bounds it (no allocation per frame).
      if (!center.valid || blobs.size() == blobs.capacity()) continue;
      blobs.push_back(center);
      best.blob[0] = static_cast<int>(blobs.size()) - 1;
    }
    best.slot[0] = 0;
    for (int i = 0; i < best.n; ++i) blobs[best.blob[i]].robot = static_cast<int>(robots.size());
    robots.push_back(best);
    ++added;
  }
  return added;
}

bool Detector::Impl::patternAroundSides(int a, int sa, int b, int sb, const int* partner, int k, Hypothesis& h,
                                        float center_rgb[3]) {
  FieldMm pts[kPatternSlots];
  int slot[kPatternSlots];
  h.n = 1;  // slot 0 (the center) is filled last
  auto add = [&](int blob, int s) {
    h.blob[h.n] = blob, h.slot[h.n] = s;
    pts[h.n - 1] = blobs[blob].at_ref, slot[h.n - 1] = s;
    ++h.n;
  };
  add(a, sa);
  add(b, sb);
  // The tolerance the search fits with where the two sides' pattern lies
  // (stretched in a grazing view).
  const FitTolerance round{opt.score_scale};
  const FitTolerance tol = search.fitToleranceAt(fitPattern(pts, slot, 2, round).position);
  const PatternPose pair = fitPattern(pts, slot, 2, tol);
  // The other slots: the free blob nearest each, within the weak sides'
  // tolerance.
  for (int s = 1; s < kPatternSlots; ++s) {
    if (s == sa || s == sb) continue;
    const FieldMm want = slotPosition(pair.position, pair.orientation, s);
    int best = -1;
    double best_d = opt.weak_side_tolerance;
    for (int j = 0; j < k; ++j) {
      const int c = partner[j];
      const double d = detector_detail::dist(blobs[c].at_ref, want);
      if (c != a && c != b && d < best_d) best = c, best_d = d;
    }
    if (best >= 0) add(best, s);
  }
  if (h.n - 1 < opt.min_side_blobs) return false;
  h.pose = fitPattern(pts, slot, h.n - 1, tol);
  if (h.pose.score < opt.min_weak_fit || overlapsAccepted(h.pose)) return false;
  // A center that peaked is the first search's to judge, unless no robot
  // holds it: then no class the searches knew placed it (extreme #759:
  // sky-blue centers under tungsten at saturation 1.23 read (176, 224,
  // 203), nearer the carpet or lines than blue's reference while blue was
  // unseen, and were dropped as implausible). It is read as an unpeaked
  // one is, and is the robot's center blob (h.blob[0]; -1: none peaked).
  h.blob[0] = -1;
  for (const auto& hit : index.within(h.pose.position, RobotPatternGeometry::kCenterBlobRadius)) {
    const FrameBlob& c = blobs[hit.first];
    if (!c.valid) continue;
    if (h.blob[0] >= 0 || c.weak || c.streak || c.robot >= 0) return false;
    h.blob[0] = static_cast<int>(hit.first);
  }
  const SeenColor seen = seenDiscColor(frame_view, camera, {h.pose.position.x, h.pose.position.y, ref_height},
                                       opt.probe_radius);
  if (seen.share < opt.min_probe_share) return false;
  // As bright as a marker (the robot's dark top is no center), and nearer
  // to the frame's yellow or blue than to any other class it learned.
  float sides = 0;
  for (int i = 1; i < h.n; ++i) sides += blobs[h.blob[i]].brightness();
  if (seen.rgb[0] + seen.rgb[1] + seen.rgb[2] < kMarkerBrightness * sides / (h.n - 1)) return false;
  const ClippedColor center(seen.rgb);
  // A center clipped white has no hue left to be nearer to a team: with
  // three sides too it is judged as a full pattern's is, the brighter team
  // (extreme #475, (252, 253, 249) by three teal dots, one a streak), but
  // not where markings cross (their arms' false colors make patterns).
  FieldMm at_ball;
  const bool white_center = center.white() && alongRay(h.pose.position, ref_height, opt.ball_radius, at_ball) &&
                            !atCrossing(at_ball);
  bool placed = h.n == kPatternSlots || white_center ? teamOfFullPattern(center, &h.team)
                                                     : teamColored(center, &h.team);
  // learnUnseenTeam probes for the full patterns whose unclipped center
  // neither team's class places.
  if (probing_unseen_team) placed = !placed && h.n == kPatternSlots && !center.clipped();
  if (!placed) return false;
  for (int i = 0; i < 3; ++i) center_rgb[i] = seen.rgb[i];
  h.rank = h.pose.score * (h.n == kPatternSlots ? 1.0 : kThreeSidePenalty) *
           kUnpeakedCenterRankFactor;
  h.confidence = h.rank;
  return true;
}

FrameBlob Detector::Impl::centerBlobAt(const FieldMm& at_ref, const float rgb[3]) const {
  FrameBlob f;
  f.at_ref = at_ref;
  f.valid = alongRay(at_ref, ref_height, opt.robot_height_yellow, f.at_team[0]) &&
            alongRay(at_ref, ref_height, opt.robot_height_blue, f.at_team[1]) &&
            alongRay(at_ref, ref_height, opt.ball_radius, f.at_ball);
  for (int c = 0; c < 3; ++c) f.rgb[c] = rgb[c];
  f.color = colorFeature(f.rgb[0], f.rgb[1], f.rgb[2]);
  return f;
}

}  // namespace dv

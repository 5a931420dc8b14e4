// The hypothesis search's completions that read the frame where the pixel
// stage found too few side blobs (hypothesis_search.h).
#include <algorithm>
#include <cmath>

#include "detection/clipped_color.h"
#include "detection/hypothesis_search.h"
#include "detection/ring_orientation.h"
#include "detection/weak_sides.h"

namespace dv {

using namespace color_class;
using detector_detail::dist;

bool HypothesisSearch::slotOutOfView(const PatternPose& pose, int slot) const {
  const FieldMm p = slotPosition(pose.position, pose.orientation, slot);
  const auto& c = camera_.calibration();
  const double w = c.image_width, h = c.image_height;
  constexpr int kRim = 8;
  for (int i = 0; i < kRim; ++i) {
    const double a = 2 * kPi * i / kRim;
    const auto px = camera_.fieldToImage({p.x + kEdgeBlobRadius * std::cos(a),
                                         p.y + kEdgeBlobRadius * std::sin(a), ref_height_});
    if (!px || px->u < -0.5 || px->v < -0.5 || px->u > w - 0.5 || px->v > h - 0.5) return true;
  }
  return false;
}

bool HypothesisSearch::slotReadsAsMarker(const PatternPose& pose, int slot, int c, ColorVec& color) const {
  if (!opt_.probe_missing_sides || !in_.frame.image) return false;
  const FieldMm p = slotPosition(pose.position, pose.orientation, slot);
  const SeenColor seen = seenDiscColor(in_.frame, camera_, {p.x, p.y, ref_height_}, opt_.probe_radius);
  if (seen.share < 1) return false;
  const float bright = seen.rgb[0] + seen.rgb[1] + seen.rgb[2];
  if (bright < kMarkerBrightness * brightness(c)) return false;
  const SeenColor carpet = carpetBeyond(pose, slot);
  const ColorVec carpet_color = colorFeature(carpet.rgb[0], carpet.rgb[1], carpet.rgb[2]);
  const bool is_carpet = carpet.share > 0 && colorDistance(carpet_color, in_.colors[kField]) <
                                                 colorDistance(carpet_color, in_.colors[kWhite]);
  if (is_carpet && bright < kOverCarpet * (carpet.rgb[0] + carpet.rgb[1] + carpet.rgb[2])) return false;
  color = colorFeature(seen.rgb[0], seen.rgb[1], seen.rgb[2]);
  return true;
}

SeenColor HypothesisSearch::carpetBeyond(const PatternPose& pose, int slot) const {
  const FieldMm p = slotPosition(pose.position, pose.orientation, slot);
  const double out = kCarpetProbeDistance / RobotPatternGeometry::kSideBlobDistance;
  const FieldPoint beyond{pose.position.x + out * (p.x - pose.position.x),
                          pose.position.y + out * (p.y - pose.position.y), 0};
  return seenDiscColor(in_.frame, camera_, beyond, opt_.probe_radius);
}

bool HypothesisSearch::weakPeakIsCarpet(const PatternPose& pose, int slot, int w) const {
  if (!opt_.probe_missing_sides || !in_.frame.image) return false;
  const SeenColor carpet = carpetBeyond(pose, slot);
  return carpet.share > 0 && brightness(w) < kOverCarpet * (carpet.rgb[0] + carpet.rgb[1] + carpet.rgb[2]) &&
         colorDistance(blobAt(w).color, colorFeature(carpet.rgb[0], carpet.rgb[1], carpet.rgb[2])) < kMinClassRadius;
}

bool HypothesisSearch::clearlySideColored(const ColorVec& color) const {
  return weakSideColor(color, in_.colors[kGreen], in_.colors[kPink], static_cast<float>(opt_.weak_color_margin)) >= 0;
}

bool HypothesisSearch::slotShowsMarker(const PatternPose& pose, int slot, int c) const {
  ColorVec color;
  return slotReadsAsMarker(pose, slot, c, color) && clearlySideColored(color);
}

bool HypothesisSearch::allSlotsShowMarkers(const PatternPose& pose, unsigned peaked, int c) const {
  ColorVec dot[4];
  bool clear = true;
  for (int s = 1; s < kPatternSlots; ++s) {
    const bool read = slotReadsAsMarker(pose, s, c, dot[s - 1]);
    if (peaked >> s & 1u) continue;
    if (slotOutOfView(pose, s) || !read) return false;
    clear = clear && clearlySideColored(dot[s - 1]);
  }
  if (clear) return true;
  // Not each clearly green or pink (a pink clipped toward white): all four
  // dots must read as markers and split into two colors by themselves, as
  // the robot's identity then splits them (robot_identity.h).
  for (int s = 1; s < kPatternSlots; ++s)
    if ((peaked >> s & 1u) && !slotReadsAsMarker(pose, s, c, dot[s - 1])) return false;
  const ColorVec prior[2] = {in_.colors[kGreen], in_.colors[kPink]};
  const ColorVec ext[1] = {blobAt(c).color};
  uint8_t labels[4];
  return twoMeans(dot, 4, prior, ext, 1, labels).separated;
}

void HypothesisSearch::completeFromTwoSides(int c, const int* nbr, int k, Hypothesis& best) {
  // Reading the frame costs: only for a center that looks like a team
  // color rather than a side color (a side blob is a center candidate too).
  auto nearer = [&](int a, int b) {
    return std::min(colorDistance(blobAt(c).color, in_.colors[a]), colorDistance(blobAt(c).color, in_.colors[b]));
  };
  // A center clipped in two channels has no reliable color: its markers
  // decide.
  const bool center_like =
      nearer(kYellow, kBlue) < nearer(kGreen, kPink) || ClippedColor(blobAt(c).rgb).saturated();
  // Whether the slots of `pose` other than slot[1], slot[2] are out of
  // view or show markers; `by_marker`: at least one shows a marker. With
  // both in view, allSlotsShowMarkers judges them (a clipped pink pair
  // splits from the robot's own green).
  auto othersShown = [&](const int* blob, const int* slot, const PatternPose& pose, int n_weak, bool& by_marker) {
    by_marker = false;
    const unsigned peaked = 1u << slot[1] | 1u << slot[2];
    bool cut = false;  // a slot out of view: a robot at the image border
    for (int s = 1; s < kPatternSlots; ++s) {
      if (peaked >> s & 1u) continue;
      if (n_weak == 0 && slotOutOfView(pose, s)) {
        cut = true;
        continue;
      }
      if (!center_like) return false;
      by_marker = true;
    }
    if (!by_marker) return true;
    if (!cut) return allSlotsShowMarkers(pose, peaked, blob[0]);
    for (int s = 1; s < kPatternSlots; ++s)
      if (!(peaked >> s & 1u) && !slotOutOfView(pose, s) && !slotShowsMarker(pose, s, blob[0])) return false;
    return true;
  };
  const FitTolerance tol = fitToleranceAt(blobAt(c).at_ref);
  auto take = [&](const int* blob, const int* slot, const PatternPose& pose) {
    const int n_weak = blobAt(blob[1]).weak + blobAt(blob[2]).weak;
    const double rank = pose.score * kFourBlobPenalty * kEdgeRankFactor * (1 - kWeakSideRankStep * n_weak);
    if (rank <= best.rank) return;
    bool by_marker;
    if (!othersShown(blob, slot, pose, n_weak, by_marker)) return;
    if (by_marker && (slot[1] - slot[2]) % 2 == 0) {
      const int a = slot[1] % 4 + 1, b = slot[2] % 4 + 1;  // the other diagonal
      for (const auto& alt : {std::array<int, 3>{0, a, b}, std::array<int, 3>{0, b, a}}) {
        const FieldMm pts[3] = {blobAt(blob[0]).at_ref, blobAt(blob[1]).at_ref, blobAt(blob[2]).at_ref};
        const PatternPose other = fitPattern(pts, alt.data(), 3, tol);
        bool unused;
        if (other.score >= opt_.min_weak_fit && othersShown(blob, alt.data(), other, n_weak, unused)) return;
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
  if (k > 0 && !in_.weak_index->points().empty()) {
    std::array<int, 64> mixed;
    const int m = sidePeaks(c, nbr, k, mixed);
    if (m > k)
      forSideBlobPairs(c, mixed.data(), m, [&](const int* blob, const int* slot, const PatternPose& pose) {
        if (blobAt(blob[1]).weak != blobAt(blob[2]).weak) take(blob, slot, pose);
      });
  }
  if (best.rank <= 0 && center_like) completeFromOneSide(c, nbr, k, best);
  if (best.rank <= 0 && center_like) completeFromCenter(c, best);
}

bool HypothesisSearch::agreesWithRing(int c, const PatternPose& pose) const {
  if (!opt_.probe_missing_sides) return true;
  const FieldMm cp = blobAt(c).at_ref;
  const auto o = ringOrientation(in_.frame, camera_, {cp.x, cp.y, ref_height_}, kMarkerBrightness * brightness(c));
  return !o || std::abs(wrapAngle(pose.orientation - *o)) <= kRingAgreement;
}

void HypothesisSearch::completeFromCenter(int c, Hypothesis& best) {
  if (!opt_.probe_missing_sides || !in_.frame.image) return;
  // Not the ball: a center nearer to the orange class than to both teams'
  // is left to the ball policy (a clipped center's color says too little).
  const ClippedColor seen(blobAt(c).rgb);
  if (!seen.saturated() && seen.distance(in_.colors[kOrange]) <
                               std::min(seen.distance(in_.colors[kYellow]), seen.distance(in_.colors[kBlue])))
    return;
  const FieldMm cp = blobAt(c).at_ref;
  const auto orientation = ringOrientation(in_.frame, camera_, {cp.x, cp.y, ref_height_},
                                           kMarkerBrightness * brightness(c));
  if (!orientation) return;
  PatternPose pose;
  pose.position = cp;
  pose.orientation = *orientation;
  pose.score = 1;
  if (!allSlotsShowMarkers(pose, 0, c)) return;
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

void HypothesisSearch::completeFromOneSide(int c, const int* nbr, int k, Hypothesis& best) {
  const FieldMm cp = blobAt(c).at_ref;
  const FitTolerance tol = fitToleranceAt(cp);
  Hypothesis found;
  int n_found = 0;
  for (int a = 0; a < k; ++a) {
    const FieldMm pa = blobAt(nbr[a]).at_ref;
    if (std::abs(dist(pa, cp) - RobotPatternGeometry::kSideBlobDistance) > kWeakPairRingTolerance) continue;
    for (int sa = 1; sa < kPatternSlots; ++sa) {
      const int blob[2] = {c, nbr[a]}, slot[2] = {0, sa};
      const FieldMm pts[2] = {cp, pa};
      const PatternPose pose = fitPattern(pts, slot, 2, tol);
      if (pose.score < opt_.min_weak_fit) continue;
      if (!allSlotsShowMarkers(pose, 1u << sa, c)) continue;
      ++n_found;
      found.n = 2;
      for (int i = 0; i < 2; ++i) found.blob[i] = blob[i], found.slot[i] = slot[i];
      found.pose = pose;
      found.rank = pose.score * kFourBlobPenalty * kEdgeRankFactor * kOneSideRankFactor;
    }
  }
  if (n_found == 1 && found.rank > best.rank) best = found;
}

}  // namespace dv

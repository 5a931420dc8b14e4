#include "detection/hypothesis_search.h"

#include <algorithm>
#include <cmath>

#include "detection/ring_orientation.h"
#include "detection/weak_sides.h"
#include "pipeline/view_stretch.h"

namespace dv {

using namespace color_class;
using detector_detail::dist;
using detector_detail::sq;

HypothesisSearch::HypothesisSearch(const CameraModel& camera) : camera_(camera) {}

void HypothesisSearch::setOptions(const DetectorOptions& opt, double ref_height, const FieldRect& area) {
  opt_ = opt;
  ref_height_ = ref_height;
  stretched_view_ = false;
  stretched_view_ = seesStretchedField(area);
}

void HypothesisSearch::find(const HypothesisInputs& in, std::vector<Hypothesis>& out) {
  in_ = in;
  top_of_ = -1;
  out.clear();
  for (int c = 0; c < in_.n_strong; ++c) {
    const Hypothesis best = bestAt(c);
    if (best.rank > 0) out.push_back(best);
  }
}

Hypothesis HypothesisSearch::bestAt(const HypothesisInputs& in, int c) {
  in_ = in;
  top_of_ = -1;
  return bestAt(c);
}

Hypothesis HypothesisSearch::bestAt(int c) {
  Hypothesis best;
  best.rank = -1;
  if (!blobAt(c).valid || blobAt(c).streak) return best;
  const bool weak_on = !in_.weak_index->points().empty();
  std::array<int, 64> nbr;
  std::array<double, 64> ang;
  std::array<double, 64> dev;
  const FieldMm cp = blobAt(c).at_ref;
  const auto& hits = in_.index->within(cp, opt_.side_search_radius);
  int k = 0;
  for (const auto& h : hits) {
    const int i = static_cast<int>(h.first);
    if (i == c || h.second < sq(kMinSideDistance)) continue;
    // A peak much darker than the center is the robot top's (chroma
    // ringing around the dots after JPEG), never a marker.
    if (darkerThanMarker(i, c)) continue;
    if (k == static_cast<int>(nbr.size())) break;
    nbr[k] = i;
    dev[k] = std::abs(std::sqrt(h.second) - RobotPatternGeometry::kSideBlobDistance);
    ++k;
  }
  // Fewer than two side blobs make a pattern only with weak peaks or the
  // frame's reading (completeFromOneSide, completeFromCenter).
  if (!weak_on && k < 2 && !(opt_.probe_missing_sides && in_.frame.image)) return best;
  if (k > kMaxNeighbors) {  // keep the ones nearest to the side blob ring
    for (int a = 0; a < kMaxNeighbors; ++a) {
      int nearest = a;
      for (int b = a + 1; b < k; ++b)
        if (dev[b] < dev[nearest]) nearest = b;
      std::swap(nbr[a], nbr[nearest]);
      std::swap(dev[a], dev[nearest]);
    }
    k = kMaxNeighbors;
  }
  for (int a = 0; a < k; ++a) {
    const FieldMm q = blobAt(nbr[a]).at_ref;
    ang[a] = std::atan2(q.y - cp.y, q.x - cp.x);
  }
  // Sort by angle (insertion sort, k <= 10).
  for (int a = 1; a < k; ++a)
    for (int b = a; b > 0 && ang[b] < ang[b - 1]; --b) {
      std::swap(ang[b], ang[b - 1]);
      std::swap(nbr[b], nbr[b - 1]);
    }
  const FitTolerance tol = fitToleranceAt(cp);
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
        pts[q + 1] = blobAt(nbr[pick[q]]).at_ref;
      }
      h.pose = fitPattern(pts, h.slot, h.n, tol);
      h.rank = h.pose.score * (m == 4 ? 1.0 : kFourBlobPenalty);
      if (h.pose.score >= opt_.min_robot_score && h.rank > best.rank) best = h;
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
  if (opt_.min_side_blobs <= 3 && best.rank < kFourBlobPenalty) {
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
  // A pattern of three side blobs that fits loosely (one of them clutter,
  // such as a shadow on the robot's top) may rank below the two of them
  // that fit tightly with the markers the frame shows.
  if (best.rank < kFourBlobPenalty * kEdgeRankFactor) completeFromTwoSides(c, nbr.data(), k, best);
  return best;
}

bool HypothesisSearch::darkerThanMarker(int i, int c) {
  if (brightness(i) >= kTopBrightness * brightness(c)) return false;
  if (!opt_.probe_missing_sides || !in_.frame.image) return true;
  if (top_of_ != c) {  // read once per center, only where a peak needs it
    top_of_ = c;
    const FieldMm cp = blobAt(c).at_ref;
    const auto top = ringDarkest(in_.frame, camera_, {cp.x, cp.y, ref_height_});
    top_floor_ = top ? std::sqrt(std::max(*top, 1.f) * brightness(c)) : -1;
  }
  return !(top_floor_ >= 0 && brightness(i) >= top_floor_);
}

FitTolerance HypothesisSearch::fitToleranceAt(const FieldMm& p) const {
  FitTolerance t{opt_.score_scale};
  if (!stretched_view_) return t;
  double dir[2];
  const double s = viewStretch(camera_, p, ref_height_, dir);
  if (s >= kMinStretch) t.stretch = s, t.along_x = dir[0], t.along_y = -dir[1];
  return t;
}

bool HypothesisSearch::seesStretchedField(const FieldRect& area) const {
  const auto& c = camera_.calibration();
  constexpr double kStep = 100;
  for (double y = area.y_min; y <= area.y_max; y += kStep)
    for (double x = area.x_min; x <= area.x_max; x += kStep) {
      const auto px = camera_.fieldToImage({x, y, ref_height_});
      if (!px || px->u < 0 || px->v < 0 || px->u > c.image_width - 1 || px->v > c.image_height - 1) continue;
      double dir[2];
      if (viewStretch(camera_, {x, y}, ref_height_, dir) >= kMinStretch) return true;
    }
  return false;
}

void HypothesisSearch::completeWithWeak(int c, const int* nbr, int k, Hypothesis& best) {
  const FieldMm cp = blobAt(c).at_ref;
  if (in_.weak_index->within(cp, opt_.side_search_radius).empty()) return;
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
    weak_tol.mm = opt_.weak_side_tolerance;
    int n_weak = findWeakSlots(pose, filled, *in_.weak_index, weak_tol, found, error);
    // A weak peak much darker than the center is the robot top's (the dark
    // rim around a pale dot), one colored as the carpet beyond the rim the
    // carpet's texture (a sun patch over a ball lit three peaks around it,
    // a robot of a ball and the carpet); neither is a marker.
    for (int s = 1; s < kPatternSlots; ++s)
      if (found[s] >= 0 && (darkerThanMarker(in_.n_strong + found[s], c) ||
                            weakPeakIsCarpet(pose, s, in_.n_strong + found[s])))
        found[s] = -1, --n_weak;
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
    for (int i = 0; i < n; ++i) h.blob[h.n] = blob[i], h.slot[h.n] = slot[i], pts[h.n++] = blobAt(blob[i]).at_ref;
    for (int s = 0; s < kPatternSlots; ++s) {
      if (found[s] < 0) continue;
      const int b = in_.n_strong + found[s];
      h.blob[h.n] = b, h.slot[h.n] = s, pts[h.n++] = blobAt(b).at_ref;
    }
    h.pose = fitPattern(pts, h.slot, h.n, tol);
    if (h.pose.score < opt_.min_weak_fit) return;
    int all_weak = n_weak;
    for (int i = 0; i < n; ++i) all_weak += blobAt(blob[i]).weak;
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
    const FieldMm pa = blobAt(nbr[a]).at_ref;
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

int HypothesisSearch::sidePeaks(int c, const int* nbr, int k, std::array<int, 64>& out) {
  int m = 0;
  for (int i = 0; i < k && m < static_cast<int>(out.size()); ++i) out[m++] = nbr[i];
  for (const auto& hit : in_.weak_index->within(blobAt(c).at_ref, opt_.side_search_radius)) {
    if (m == static_cast<int>(out.size())) break;
    const int w = in_.n_strong + static_cast<int>(hit.first);
    if (hit.second >= sq(kMinSideDistance) && !darkerThanMarker(w, c)) out[m++] = w;
  }
  return m;
}

}  // namespace dv

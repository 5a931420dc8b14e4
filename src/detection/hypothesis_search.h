#pragma once
// Patterns of blobs -> robot hypotheses (thesis §5.3.3): for each blob
// taken as a robot's center, the best placement of the robot pattern on
// the blobs around it. Four side blobs rank first, then three; where the
// pixel stage found fewer, weak peaks (weak_sides.h), the image border and
// the colors the frame shows at the empty slots (seen_color.h,
// ring_orientation.h) complete the pattern, each at a lower rank. Which
// hypotheses become robots is the detector's choice (selectRobots).
// hypothesis_search.cpp holds the search over blobs and weak peaks,
// hypothesis_frame_reads.cpp the completions that read the frame.
#include <array>
#include <cmath>
#include <vector>

#include "detection/blob_index.h"
#include "detection/color_classes.h"
#include "detection/detector.h"
#include "detection/frame_blob.h"
#include "detection/pattern_fit.h"
#include "detection/robot_hypothesis.h"
#include "detection/seen_color.h"

namespace dv {

// One frame as the search reads it; owned by the detector.
struct HypothesisInputs {
  const std::vector<FrameBlob>* blobs = nullptr;
  int n_strong = 0;                // blobs [0, n_strong) peaked, the rest are weak peaks
  BlobIndex* index = nullptr;      // the strong blobs' positions (at_ref)
  BlobIndex* weak_index = nullptr;  // the weak peaks', blob n_strong + i at point i
  // The class colors the frame's colors are judged by (color_class::Id).
  const ColorVec* colors = nullptr;
  FrameView frame;  // may be empty: nothing is read from the image then
};

class HypothesisSearch {
 public:
  explicit HypothesisSearch(const CameraModel& camera);
  // ref_height: the plane (mm) at_ref lies on; area: the field the
  // camera's view is checked for stretch over (fitToleranceAt).
  void setOptions(const DetectorOptions& opt, double ref_height, const FieldRect& area);

  // The best hypothesis of each center blob that has one, into `out`.
  void find(const HypothesisInputs& in, std::vector<Hypothesis>& out);
  // Blob c's best hypothesis as a center (rank <= 0: none).
  Hypothesis bestAt(const HypothesisInputs& in, int c);
  // How closely blobs around `p` (search plane) must fit the pattern: the
  // score scale, stretched along the viewing ray where the camera sees the
  // field at a grazing angle (view_stretch.h; from the same stretch on where
  // the pixel stage whitens the gradient, so other views fit as before).
  FitTolerance fitToleranceAt(const FieldMm& p) const;
  // A side blob a completion starts from lies this near (mm) the center's
  // ring of side blobs.
  static constexpr double kWeakPairRingTolerance = 15;

 private:
  Hypothesis bestAt(int c);
  const FrameBlob& blobAt(int i) const { return (*in_.blobs)[i]; }
  float brightness(int i) const { return blobAt(i).brightness(); }
  // Whether peak i is too dark to be a marker of center c: below
  // kTopBrightness of the center's brightness and, where the frame shows
  // the robot's top along the side-dot ring (its darkest point), nearer
  // to the top than to the center in the ratio of brightnesses (below
  // their geometric mean). A gamma raises every brightness to a power,
  // which keeps that midpoint in place: under gamma 1.6 a teal dot reads a
  // third of an amber center and sixteen times the black top; a dark
  // ringing peak on the top stays nearer the top.
  bool darkerThanMarker(int i, int c);

  // Whether the camera sees any part of `area` stretched enough for
  // fitToleranceAt to stretch its tolerance, on a 100 mm lattice; a camera
  // looking down sees none, and skips the per-blob stretch.
  bool seesStretchedField(const FieldRect& area) const;

  // Weak peaks for the side blobs a center's pattern lacks (weak_sides.h):
  // the missing slot of its best three-side pattern; else the missing slots
  // of two side blobs that fit the pattern tightly with the center (three
  // or four sides in all); else, from one side blob, all three others;
  // else, where no two side blobs fit, from any two side peaks, weak or
  // not, weak peaks in the other slots, all but one that shows a marker in
  // the frame (slotShowsMarker). Ranks are a little below those of
  // patterns of blobs alone, a step lower per weak peak; `best` is replaced
  // when one ranks higher.
  void completeWithWeak(int c, const int* nbr, int k, Hypothesis& best);
  // The peaks that may be center c's side blobs: its neighbours nbr[0, k)
  // (blobs), then the weak peaks within reach that are not too near it nor
  // as dark as a robot top. Returns how many `out` holds.
  int sidePeaks(int c, const int* nbr, int k, std::array<int, 64>& out);

  // Whether the blob of `slot` at `pose` (on the search plane) cannot be
  // seen whole: part of its disc lies outside the image.
  bool slotOutOfView(const PatternPose& pose, int slot) const;

  // Whether the frame shows a side marker at `slot` of `pose` where no peak
  // was found: the color read there (seen_color.h), in full view, is at
  // least kMarkerBrightness as bright as the center blob `c` (a dark
  // color's chromaticity is unreliable, and the robot top is dark), at
  // least kOverCarpet as bright as the carpet just beyond the robot's rim
  // in the same direction where that reads as carpet rather than a line (a
  // green dot has the carpet's chromaticity; the slots of a pattern made of
  // clutter lie on the carpet), and clearly nearer to the green or the
  // pink class than to the other.
  bool slotShowsMarker(const PatternPose& pose, int slot, int c) const;
  // slotShowsMarker's reading without its color test: in full view, bright
  // enough and over the carpet; `color` is what the frame shows there.
  bool slotReadsAsMarker(const PatternPose& pose, int slot, int c, ColorVec& color) const;
  // Clearly nearer to the green or the pink class than to the other.
  bool clearlySideColored(const ColorVec& color) const;
  // The carpet just beyond the robot's rim, kCarpetProbeDistance mm from
  // its center in the direction of `slot`, as the frame shows it.
  SeenColor carpetBeyond(const PatternPose& pose, int slot) const;
  // Whether weak peak `w` in `slot` of `pose` is colored as that carpet,
  // within a color's noise (kMinClassRadius), and not kOverCarpet as
  // bright: the carpet's texture, which a sun patch lights into peaks, and
  // no marker (under dark tungsten in video real dots come out as gray as
  // the carpet, but brighter).
  bool weakPeakIsCarpet(const PatternPose& pose, int slot, int w) const;
  // Whether every slot of `pose` not in `peaked` (bit s: slot s has a
  // peak) is in full view and shows a marker: each clearly green or pink,
  // or, where all four slots read as markers, the four splitting into two
  // colors by themselves (twoMeans, the center color external): a pink
  // clipped toward white beside the robot's green is clearly nearer to
  // neither class, and the robot's identity splits its dots the same way.
  bool allSlotsShowMarkers(const PatternPose& pose, unsigned peaked, int c) const;

  // A center blob and two side blobs that fit the pattern tightly, where
  // each of the other two slots is either not seen whole (slotOutOfView: a
  // robot at the image border) or shows a marker that did not peak
  // (slotShowsMarker: a dot whose blurred chroma runs into the carpet, as
  // after JPEG's half-resolution chroma at 1224 x 1024; with both in view,
  // allSlotsShowMarkers). Where no such pair
  // of blobs exists, a weak peak may stand for one of the two when both
  // other slots show markers. A diagonal pair (front-left and back-right,
  // or back-left and front-right: 155 degrees apart either way) fits both
  // diagonals; where markers show at the other slots of both placements
  // (far, blurred dots), the pose is one of two and the pattern is not
  // taken. Ranked below every pattern with three side blobs (tried also
  // where one of three loosely fitting ranks lower); an id left open is a
  // guess unless teammates or a track tell it.
  void completeFromTwoSides(int c, const int* nbr, int k, Hypothesis& best);

  // A center blob (team-colored) and one side blob on the ring, where the
  // frame shows markers at all three other slots (allSlotsShowMarkers): a
  // robot whose other dots did not peak (pale dots beside a dark top, their
  // chroma lost to desaturation or clipping). Each slot the side blob may
  // fill is tried; the pose is taken only where exactly one shows markers
  // at the others (else the orientation would be a guess). Ranked below
  // every pattern of two side peaks.
  void completeFromOneSide(int c, const int* nbr, int k, Hypothesis& best);

  // A center blob (team-colored, not the ball's) without a side peak on
  // its ring: the frame is read along the side-blob ring, and where exactly
  // one orientation puts all four slots on bright points (markers beside
  // the dark top) and each slot then shows a marker in full view
  // (allSlotsShowMarkers), that is the robot: pale dots that made no peak at
  // all. The orientation is refined from where the bright arcs lie. Ranked
  // below every pattern with a side peak; reported only with its id known.
  void completeFromCenter(int c, Hypothesis& best);

  // Whether `pose` agrees with the orientation the ring around center c
  // shows (ring_orientation.h), where it shows one (else true).
  bool agreesWithRing(int c, const PatternPose& pose) const;

  // Center blob c with each pair of its neighbours nbr[0, k) that lie on the
  // side-blob ring as far apart in angle as two slots: fn(blob, slot, pose)
  // with blob = {c, a, b}, slot = {0, sa, sb} and the pattern fitted to
  // them, where the fit scores at least min_weak_fit.
  template <class Fn>
  void forSideBlobPairs(int c, const int* nbr, int k, Fn&& fn) const;

  int top_of_ = -1;      // the center whose top floor top_floor_ holds
  float top_floor_ = -1;  // geometric mean of its brightness and its ring's darkest (-1: none)

  static constexpr int kMaxNeighbors = 10;        // side blob candidates per center
  static constexpr double kMinSideDistance = 30;  // mm, closer blobs cannot be side blobs
  static constexpr double kFourBlobPenalty = 0.5;  // rank factor for a missing side blob
  // Patterns completed with weak peaks rank this much lower per weak side.
  static constexpr double kWeakSideRankStep = 0.1;
  // Two side blobs a weak completion starts from: their angle around the
  // center blob (rad) near the pattern's (their distance: kWeakPairRingTolerance).
  static constexpr double kWeakPairAngleTolerance = 0.35;
  // A robot cut by the image border (center and two side blobs, the other
  // two slots outside the image) ranks at this fraction of a three-side
  // pattern's rank; a side blob counts as outside when any point of its disc
  // is (the pixel stage takes peaks only where that disc is seen).
  static constexpr double kEdgeRankFactor = 0.6;
  // A pattern of a center and one side blob, its other slots read from the
  // frame, ranks at this fraction of one of a center and two; one of the
  // center alone at this fraction of that.
  static constexpr double kOneSideRankFactor = 0.8;
  // A pose agrees with the orientation read along its ring within this (rad):
  // the ring reads it to a degree or two, and the two placements a diagonal
  // pair of side blobs fits lie about 90 degrees apart.
  static constexpr double kRingAgreement = 0.5;
  // A marker read from the frame is this much brighter than the carpet read
  // kCarpetProbeDistance mm from the robot's center (its rim is at 90 mm;
  // the default green marker is 1.7 times as bright as the carpet).
  static constexpr float kOverCarpet = 1.25f;
  static constexpr double kCarpetProbeDistance = 115;
  static constexpr double kEdgeBlobRadius = RobotPatternGeometry::kSideBlobRadius;

  CameraModel camera_;
  DetectorOptions opt_;
  double ref_height_ = 140;
  bool stretched_view_ = false;  // some field point in view is stretched (fitToleranceAt)
  HypothesisInputs in_;
};

// The angle of `slot` around the center in the robot's frame.
inline double slotAngle(int slot) {
  const FieldMm o = patternOffset(slot);
  return std::atan2(o.y, o.x);
}

template <class Fn>
inline void HypothesisSearch::forSideBlobPairs(int c, const int* nbr, int k, Fn&& fn) const {
  const FieldMm cp = blobAt(c).at_ref;
  auto onRing = [&](const FieldMm& p) {
    return std::abs(detector_detail::dist(p, cp) - RobotPatternGeometry::kSideBlobDistance) <= kWeakPairRingTolerance;
  };
  auto angleAround = [&](const FieldMm& p) { return std::atan2(p.y - cp.y, p.x - cp.x); };
  const FitTolerance tol = fitToleranceAt(cp);
  for (int a = 0; a < k; ++a) {
    const FieldMm pa = blobAt(nbr[a]).at_ref;
    if (!onRing(pa)) continue;
    for (int b = a + 1; b < k; ++b) {
      const FieldMm pb = blobAt(nbr[b]).at_ref;
      if (!onRing(pb)) continue;
      const double seen = wrapAngle(angleAround(pb) - angleAround(pa));
      for (int sa = 1; sa < kPatternSlots; ++sa)
        for (int sb = 1; sb < kPatternSlots; ++sb) {
          if (sa == sb || std::abs(wrapAngle(seen - (slotAngle(sb) - slotAngle(sa)))) > kWeakPairAngleTolerance)
            continue;
          const int blob_ids[3] = {c, nbr[a], nbr[b]}, slot[3] = {0, sa, sb};
          const FieldMm pts[3] = {cp, pa, pb};
          const PatternPose pose = fitPattern(pts, slot, 3, tol);
          if (pose.score >= opt_.min_weak_fit) fn(blob_ids, slot, pose);
        }
    }
  }
}

}  // namespace dv

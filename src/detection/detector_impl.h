#pragma once
// The detector's state and stages (detector.h), shared by the files that
// hold one stage each: detector.cpp (the frame: blobs in, detections out),
// detector_hypotheses.cpp (patterns of blobs -> robot hypotheses),
// detector_identities.cpp (color classes -> team and id), detector_tracks.cpp
// (robot tracks and identity hysteresis), detector_balls.cpp (the ball
// candidates, judged by ball_color.h and selected by ball_policy.h).
// Private to those files.
#include "detection/detector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "detection/ball_color.h"
#include "detection/ball_tracker.h"
#include "detection/blob_index.h"
#include "detection/border_balls.h"
#include "detection/clipped_color.h"
#include "detection/color_classes.h"
#include "detection/pattern_fit.h"
#include "detection/robot_tracker.h"
#include "detection/weak_sides.h"
#include "pipeline/view_stretch.h"

namespace dv {
namespace detector_detail {

using namespace color_class;  // the class ids (ball_color.h)

constexpr int kMaxNeighbors = 10;       // side blob candidates per center
constexpr int kMaxSlotCandidates = 3;   // blobs per predicted slot (tracking)
constexpr double kMinSideDistance = 30;  // mm, closer blobs cannot be side blobs
constexpr double kFourBlobPenalty = 0.5;  // rank factor for a missing side blob
// Patterns completed with weak peaks rank this much lower per weak side.
constexpr double kWeakSideRankStep = 0.1;
// Two side blobs a weak completion starts from: their distance to the center
// blob (mm) and their angle around it (rad) near the pattern's.
constexpr double kWeakPairRingTolerance = 15;
constexpr double kWeakPairAngleTolerance = 0.35;
// A robot cut by the image border (center and two side blobs, the other
// two slots outside the image) ranks at this fraction of a three-side
// pattern's rank; a side blob counts as outside when any point of its disc
// is (the pixel stage takes peaks only where that disc is seen).
constexpr double kEdgeRankFactor = 0.6;
// A pattern of a center and one side blob, its other slots read from the
// frame, ranks at this fraction of one of a center and two; one of the
// center alone at this fraction of that.
constexpr double kOneSideRankFactor = 0.8;
// A pose agrees with the orientation read along its ring within this (rad):
// the ring reads it to a degree or two, and the two placements a diagonal
// pair of side blobs fits lie about 90 degrees apart.
constexpr double kRingAgreement = 0.5;

// Brightness (r + g + b) as a share of the center blob's: a side blob is
// at least kTopBrightness (the markers are about as bright as the centers;
// darker peaks lie on the robot top), a marker read from the frame where no
// peak was found at least kMarkerBrightness.
constexpr float kTopBrightness = 0.33f, kMarkerBrightness = 0.5f;
// A marker read from the frame is this much brighter than the carpet read
// kCarpetProbeDistance mm from the robot's center (its rim is at 90 mm;
// the default green marker is 1.7 times as bright as the carpet).
constexpr float kOverCarpet = 1.25f;
constexpr double kCarpetProbeDistance = 115;
constexpr double kEdgeBlobRadius = RobotPatternGeometry::kSideBlobRadius;
// Streak score at which a fast-ball candidate counts at full strength.
constexpr double kStreakFullStrength = 0.6;

inline ColorVec feature(const ColorRef& c) { return colorFeature(c.r, c.g, c.b); }

struct FrameBlob {
  FieldMm at_ref;     // on the plane hypotheses are searched on
  FieldMm at_team[2]; // at the yellow / blue robot height
  FieldMm at_ball;    // at the ball center height
  ColorVec color;
  float rgb[3] = {0, 0, 0};
  float score = 0;
  bool valid = false;
  bool weak = false;  // a weak peak (BlobList::weak), listed after the blobs
  bool streak = false;  // a fast-ball candidate: never part of a robot
  int robot = -1;  // accepted robot using this blob
  bool implausible_center = false;  // its robot was dropped for its center color
};

inline double sq(double v) { return v * v; }
inline double slotAngle(int slot) {
  const FieldMm o = patternOffset(slot);
  return std::atan2(o.y, o.x);
}

inline double dist(const FieldMm& a, const FieldMm& b) { return std::hypot(a.x - b.x, a.y - b.y); }

}  // namespace detector_detail
using namespace detector_detail;

struct Detector::Impl {
  CameraModel camera;
  FieldModel field;
  DetectorOptions opt;
  Eigen::Vector3d cam_pos;
  double ref_height = 140;
  FieldRect ball_area;
  bool stretched_view = false;  // some field point in view is stretched (fitToleranceAt)

  ColorClass classes[kNumClasses];
  ColorVec frame_color[kNumClasses];  // this frame's class colors
  bool frame_seen[kNumClasses];       // class had samples in this frame
  float frame_spread[kNumClasses];    // rms distance of its samples to frame_color (0: unknown)
  NeutralColor neutral;               // the lines' color this frame (BlobList::neutral)
  float yellow_hue_min = 0;           // of this frame's yellow centers (classifyRobots)
  float min_saturation = 0;
  DetectionHealth health;             // of the last frame
  ColorMap color_map;                 // references -> this camera's colors

  std::vector<FrameBlob> blobs;
  BlobIndex index;       // the blobs
  BlobIndex weak_index;  // the weak peaks, blob n_strong + i at point i
  int n_strong = 0;
  std::vector<Hypothesis> hyps;
  std::vector<Hypothesis> robots;  // accepted
  RobotTracker tracker;
  BallTracker ball_tracker;
  std::vector<FieldMm> robot_positions;  // of the accepted robots, for the ball tracker
  std::vector<BallCandidate> ball_cands;
  std::vector<ColorVec> samples;
  std::vector<uint8_t> labels;
  std::vector<int> sample_owner;
  std::vector<float> score_buf;
  double last_t = 0;
  bool have_frame = false;
  bool new_scene = false;  // this frame dropped the history (unrelated scene)

  Impl(const CameraModel& cam, const FieldModel& f, const DetectorOptions& o);

  // Takes new options between frames; tracks and learned colors stay.
  void setOptions(const DetectorOptions& o);

  void reset();

  double teamHeight(Team t) const {
    return t == Team::Yellow ? opt.robot_height_yellow : opt.robot_height_blue;
  }

  // Moves a point along its camera ray from plane z0 to plane z1. This is
  // exactly fieldToImage followed by imageToField (the ray does not depend
  // on the lens distortion), without the distortion solve per blob.
  bool alongRay(const FieldMm& p, double z0, double z1, FieldMm& out) const {
    const double cz = cam_pos.z();
    if (cz <= z0 + 1 || cz <= z1 + 1) return false;
    const double s = (cz - z1) / (cz - z0);
    out = {cam_pos.x() + s * (p.x - cam_pos.x()), cam_pos.y() + s * (p.y - cam_pos.y())};
    return true;
  }

  // ---------------------------------------------------------------- frame
  void prepare(const BlobList& list);

  // ------------------------------------------- position based hypotheses
  void findHypotheses();

  // How closely blobs around `p` (search plane) must fit the pattern: the
  // score scale, stretched along the viewing ray where the camera sees the
  // field at a grazing angle (view_stretch.h; from the same stretch on where
  // the pixel stage whitens the gradient, so other views fit as before).
  FitTolerance fitToleranceAt(const FieldMm& p) const;

  // Whether the camera sees any part of the field (plus boundary) stretched
  // enough for fitToleranceAt to stretch its tolerance, on a 100 mm lattice;
  // a camera looking down sees none, and skips the per-blob stretch.
  bool seesStretchedField() const;

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
  // clutter lie on the carpet), and clearly
  // nearer to the green or the pink class than to the other.
  bool slotShowsMarker(const PatternPose& pose, int slot, int c) const;

  // Brightness (r + g + b) of blob b.
  float brightness(int b) const { return blobs[b].rgb[0] + blobs[b].rgb[1] + blobs[b].rgb[2]; }

  // A center blob and two side blobs that fit the pattern tightly, where
  // each of the other two slots is either not seen whole (slotOutOfView: a
  // robot at the image border) or shows a marker that did not peak
  // (slotShowsMarker: a dot whose blurred chroma runs into the carpet, as
  // after JPEG's half-resolution chroma at 1224 x 1024). Where no such pair
  // of blobs exists, a weak peak may stand for one of the two when both
  // other slots show markers. A diagonal pair (front-left and back-right,
  // or back-left and front-right: 155 degrees apart either way) fits both
  // diagonals; where markers show at the other slots of both placements
  // (far, blurred dots), the pose is one of two and the pattern is not
  // taken. Ranked below every pattern with three side blobs; an id left
  // open is a guess unless teammates or a track tell it.
  void completeFromTwoSides(int c, const int* nbr, int k, Hypothesis& best);

  // A center blob (team-colored) and one side blob on the ring, where the
  // frame shows markers at all three other slots, each in full view: a
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
  // (slotShowsMarker), that is the robot: pale dots that made no peak at
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
  void forSideBlobPairs(int c, const int* nbr, int k, Fn&& fn) const {
    const FieldMm cp = blobs[c].at_ref;
    auto onRing = [&](const FieldMm& p) {
      return std::abs(dist(p, cp) - RobotPatternGeometry::kSideBlobDistance) <= kWeakPairRingTolerance;
    };
    auto angleAround = [&](const FieldMm& p) { return std::atan2(p.y - cp.y, p.x - cp.x); };
    const FitTolerance tol = fitToleranceAt(cp);
    for (int a = 0; a < k; ++a) {
      const FieldMm pa = blobs[nbr[a]].at_ref;
      if (!onRing(pa)) continue;
      for (int b = a + 1; b < k; ++b) {
        const FieldMm pb = blobs[nbr[b]].at_ref;
        if (!onRing(pb)) continue;
        const double seen = wrapAngle(angleAround(pb) - angleAround(pa));
        for (int sa = 1; sa < kPatternSlots; ++sa)
          for (int sb = 1; sb < kPatternSlots; ++sb) {
            if (sa == sb || std::abs(wrapAngle(seen - (slotAngle(sb) - slotAngle(sa)))) > kWeakPairAngleTolerance)
              continue;
            const int blob[3] = {c, nbr[a], nbr[b]}, slot[3] = {0, sa, sb};
            const FieldMm pts[3] = {cp, pa, pb};
            const PatternPose pose = fitPattern(pts, slot, 3, tol);
            if (pose.score >= opt.min_weak_fit) fn(blob, slot, pose);
          }
      }
    }
  }

  bool overlapsAccepted(const PatternPose& pose, const Hypothesis* skip = nullptr) const;

  void selectRobots();

  // ------------------------------------------------------ color classes
  // Clutter (carpet noise, line crossings) can line up like a pattern. A
  // robot's center must look like this frame's yellow or blue rather than
  // like the field or a white line; the team colors come from clustering
  // the centers first, so no fixed hue is involved.
  // color_classes.h's orderByRatio over `samples` and `labels`, against
  // the lines' white of this frame.
  void orderByRatio(TwoMeansResult& r, int num, int den);
  // Center blob colors of the robot hypotheses in two classes, yellow vs
  // blue, with green and pink as the external colors (eq. 5.24); the labels
  // are left in `labels`.
  TwoMeansResult clusterCenters();

  // Drops the robots whose center looks like the field or a line more than
  // like its team's color, marks those centers implausible, and returns how
  // many were dropped.
  int dropImplausibleCenters();

  void learnClass(int a, int b, const TwoMeansResult& r);

  void classifyRobots();

  // Where no side blob of this frame is pink (pale dots that peak as none,
  // clipped toward the lines' white), the pink class would be only what
  // earlier frames or the reference say: the colors the frame shows at the
  // robots' unfilled slots (as bright as markers) are clustered with the
  // side blobs (in `samples`), and a cluster redder than the lines' white
  // (orderByRatio) is this frame's pink.
  void pinkFromUnseenSlots();

  // The side slots of `r` that neither a blob nor a weak peak filled: the
  // color the camera saw there (seen_color.h), when clearly nearer to the
  // robot's own `green` or `pink`, sets the slot's marker.
  void probeMissingSides(Hypothesis& r, const ColorVec& green, const ColorVec& pink,
                         std::array<MarkerColor, 4>& colors) const;

  // Refit at the team's height (pattern offsets are mm on the robot top).
  // Weak peaks sit less exactly than blobs: where the center and three side
  // blobs are blobs, those alone give the pose.
  void refit(Hypothesis& h) const;

  int weakCount(const Hypothesis& h) const {
    int n = 0;
    for (int i = 0; i < h.n; ++i) n += blobs[h.blob[i]].weak;
    return n;
  }

  int nearestOf(const ColorVec& c, int a, int b) const {
    return colorDistance(c, frame_color[a]) <= colorDistance(c, frame_color[b]) ? a : b;
  }

  // ----------------------------------------------------------- tracking
  // The robot tracker (robot_tracker.h) over this frame's robots; a frame
  // that shows an unrelated scene drops the ball tracks too.
  void track(double t);

  // A track no robot of this frame continued: two or more of its blobs
  // around the predicted blob positions (§5.3.6), colors agreeing with its
  // identity, make a robot appended to `out`.
  bool recoverTrack(const RobotTrack& tr, int k, std::vector<Hypothesis>& out);

  // --------------------------------------------------------------- balls
  void findBalls(double t, bool tracking, Detections& out);
  // This frame's colors for the ball's color judge (ball_color.h).
  FrameColors ball_colors;

  std::vector<FieldMm> raw_positions;
  double plane_height = 150;

  // Balls cut by the image border (border_balls.h), found in the frame;
  // the finder is made for the ball radius it was built with.
  std::optional<BorderBallFinder> border_finder;
  std::vector<BorderBall> border_balls;

  FrameView frame_view;  // the frame being processed (may be empty)

  void process(const BlobList& list, double t, Detections& out, const FrameView& frame);
};

}  // namespace dv

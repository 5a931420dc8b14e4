#include "detection/detector.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <string>

#include "core/error.h"
#include "detection/blob_index.h"
#include "detection/clipped_color.h"
#include "detection/color_classes.h"
#include "detection/pattern_fit.h"
#include "detection/weak_sides.h"
#include "pipeline/view_stretch.h"

namespace dv {
namespace {

// Color classes, in the order of DetectorOptions' references.
enum ColorClassId { kYellow = 0, kBlue, kGreen, kPink, kOrange, kField, kWhite, kNumClasses };

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
// Robots a frame and the tracks must both have before their overlap can say
// whether the frame continues the tracked scene.
constexpr int kSceneCheckMinRobots = 4;
// Streak score at which a fast-ball candidate counts at full strength.
constexpr double kStreakFullStrength = 0.6;

ColorVec feature(const ColorRef& c) { return colorFeature(c.r, c.g, c.b); }

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

struct Hypothesis {
  int blob[kPatternSlots];
  int slot[kPatternSlots];
  int n = 0;
  PatternPose pose;  // fitted at the search height, then at the team height
  double rank = 0;
  double confidence = 0;
  Team team = Team::Yellow;
  int id = 0;
  int track = -1;
  std::array<MarkerColor, 4> colors{};  // side colors, valid where seen
  uint8_t seen_sides = 0;               // bit s-1 set: slot s was seen
  // The id was seen whole, follows from the ids others hold, or comes from
  // a track that once saw the robot whole.
  bool id_known = false;
  bool fullPattern() const { return seen_sides == 0xF; }
};

struct RobotTrack {
  Team team = Team::Yellow;  // committed identity
  int id = 0;
  Team pending_team = Team::Yellow;  // contrary evidence being counted
  int pending_id = -1;
  int pending_count = 0;
  bool id_certain = false;  // seen with all four side blobs at least once
  FieldMm pos[2];  // [1] newest
  double orientation[2] = {0, 0};
  double t[2] = {0, 0};
  int history = 0;  // valid entries in pos/orientation/t (1 or 2)
  bool confirmed = false;
  // prediction for the current frame
  FieldMm predicted;
  double predicted_orientation = 0;
  double uncertainty = 0;
};

struct BallTrack {
  FieldMm pos[2];
  double t[2] = {0, 0};
  int history = 0;
  int hits = 0;
  bool confirmed = false;
  FieldMm predicted;
  double gate = 0;       // around the prediction
  double kick_gate = 0;  // around the last position, next to a robot
};

struct BallCandidate {
  int blob = -1;
  FieldMm pos;
  double confidence = 0;
  int track = -1;
};

double sq(double v) { return v * v; }
double slotAngle(int slot) {
  const FieldMm o = patternOffset(slot);
  return std::atan2(o.y, o.x);
}

// Share of the object's color in a streak's mean color (chromaticity
// weight, which favours the brighter ball over the carpet): a streak's color
// disc lies where the ball covered the cells for at least half the exposure.
constexpr float kStreakMinShare = 0.5f;
constexpr int kStreakShareSteps = 6;

// Distance from a streak's color to the mix of `field` and `object` with the
// object's share between kStreakMinShare and 1.
float streakColorDistance(const ClippedColor& seen, const ColorVec& field, const ColorVec& object) {
  float best = std::numeric_limits<float>::max();
  for (int i = 0; i < kStreakShareSteps; ++i) {
    const float a = kStreakMinShare + (1.f - kStreakMinShare) * i / (kStreakShareSteps - 1);
    best = std::min(best, seen.distance(colorMix(field, 1.f - a, object, a, object, 0.f)));
  }
  return best;
}
double dist(const FieldMm& a, const FieldMm& b) { return std::hypot(a.x - b.x, a.y - b.y); }

}  // namespace

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
  ColorMap color_map;                 // references -> this camera's colors

  std::vector<FrameBlob> blobs;
  BlobIndex index;       // the blobs
  BlobIndex weak_index;  // the weak peaks, blob n_strong + i at point i
  int n_strong = 0;
  std::vector<Hypothesis> hyps;
  std::vector<Hypothesis> robots;  // accepted
  std::vector<RobotTrack> tracks;
  std::vector<BallTrack> ball_tracks;
  std::vector<BallCandidate> ball_cands;
  std::vector<int> track_match;      // per accepted robot: track index or -1
  std::vector<uint8_t> track_taken;  // per track
  std::vector<ColorVec> samples;
  std::vector<uint8_t> labels;
  std::vector<int> sample_owner;
  std::vector<float> score_buf;
  double last_t = 0;
  bool have_frame = false;
  bool new_scene = false;  // this frame dropped the history (unrelated scene)

  Impl(const CameraModel& cam, const FieldModel& f, const DetectorOptions& o)
      : camera(cam), field(f), opt(o), cam_pos(cam.position()) {
    ball_area = field.withBoundary();
    stretched_view = seesStretchedField();
    setOptions(o);
    blobs.reserve(4096);
    hyps.reserve(1024);
    robots.reserve(64);
    tracks.reserve(64);
    ball_tracks.reserve(16);
    ball_cands.reserve(1024);
    track_match.reserve(64);
    track_taken.reserve(64);
    samples.reserve(512);
    labels.reserve(512);
    sample_owner.reserve(512);
    score_buf.reserve(512);
    reset();
  }

  // Takes new options between frames; tracks and learned colors stay.
  void setOptions(const DetectorOptions& o) {
    opt = o;
    ref_height = 0.5 * (opt.robot_height_yellow + opt.robot_height_blue);
    const ColorRef* refs[kNumClasses] = {&opt.ref_yellow, &opt.ref_blue,   &opt.ref_green,
                                         &opt.ref_pink,   &opt.ref_orange, &opt.ref_field,
                                         &opt.ref_white};
    for (int k = 0; k < kNumClasses; ++k) classes[k].reference = feature(*refs[k]);
  }

  void reset() {
    for (auto& c : classes) c.reset();
    color_map.reset();
    tracks.clear();
    ball_tracks.clear();
    have_frame = false;
  }

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

  // A ball predicted at p from `from`, mirrored back at the walls (ball
  // radius from them) its straight course would cross: a bounce.
  FieldMm reflectAtWalls(FieldMm from, FieldMm p) const {
    const double r = opt.ball_radius;
    auto mirror = [](double v0, double v, double lo, double hi) {
      if (hi <= lo || v0 < lo || v0 > hi) return v;  // not between the walls
      if (v > hi) v = std::max(lo, 2 * hi - v);
      if (v < lo) v = std::min(hi, 2 * lo - v);
      return v;
    };
    return {mirror(from.x, p.x, ball_area.x_min + r, ball_area.x_max - r),
            mirror(from.y, p.y, ball_area.y_min + r, ball_area.y_max - r)};
  }

  // ---------------------------------------------------------------- frame
  void prepare(const BlobList& list) {
    blobs.clear();
    auto& pts = index.points();
    auto& weak_pts = weak_index.points();
    pts.clear();
    weak_pts.clear();
    n_strong = static_cast<int>(list.blobs.size());
    const double z0 = list.plane_height;
    const size_t n_weak = opt.weak_sides ? list.weak.size() : 0;
    for (size_t i = 0; i < list.blobs.size() + n_weak; ++i) {
      const bool weak = i >= list.blobs.size();
      const Blob& b = weak ? list.weak[i - list.blobs.size()] : list.blobs[i];
      FrameBlob f;
      f.weak = weak;
      f.valid = alongRay(b.position, z0, ref_height, f.at_ref) &&
                alongRay(b.position, z0, opt.robot_height_yellow, f.at_team[0]) &&
                alongRay(b.position, z0, opt.robot_height_blue, f.at_team[1]) &&
                alongRay(b.position, z0, opt.ball_radius, f.at_ball) &&
                std::isfinite(b.position.x) && std::isfinite(b.position.y);
      f.color = colorFeature(b.rgb[0], b.rgb[1], b.rgb[2]);
      for (int c = 0; c < 3; ++c) f.rgb[c] = b.rgb[c];
      f.score = b.score;
      f.streak = b.streak;
      blobs.push_back(f);
      // Invalid blobs and streaks are put far away so that no query finds them.
      (weak ? weak_pts : pts).push_back(f.valid && !f.streak ? f.at_ref : FieldMm{1e12, 1e12});
    }
    index.build();
    if (!weak_pts.empty()) weak_index.build();
  }

  // ------------------------------------------- position based hypotheses
  void findHypotheses() {
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
      if (k < (weak_on ? 1 : 2)) continue;
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

  // How closely blobs around `p` (search plane) must fit the pattern: the
  // score scale, stretched along the viewing ray where the camera sees the
  // field at a grazing angle (view_stretch.h; from the same stretch on where
  // the pixel stage whitens the gradient, so other views fit as before).
  FitTolerance fitToleranceAt(const FieldMm& p) const {
    FitTolerance t{opt.score_scale};
    if (!stretched_view) return t;
    double dir[2];
    const double s = viewStretch(camera, p, ref_height, dir);
    if (s >= kMinStretch) t.stretch = s, t.along_x = dir[0], t.along_y = -dir[1];
    return t;
  }

  // Whether the camera sees any part of the field (plus boundary) stretched
  // enough for fitToleranceAt to stretch its tolerance, on a 100 mm lattice;
  // a camera looking down sees none, and skips the per-blob stretch.
  bool seesStretchedField() const {
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

  // Weak peaks for the side blobs a center's pattern lacks (weak_sides.h):
  // the missing slot of its best three-side pattern; else the missing slots
  // of two side blobs that fit the pattern tightly with the center (three
  // or four sides in all); else, from one side blob, all three others. Ranks
  // are a little below those of patterns of blobs alone; `best` is replaced
  // when one ranks higher.
  void completeWithWeak(int c, const int* nbr, int k, Hypothesis& best) {
    const FieldMm cp = blobs[c].at_ref;
    if (weak_index.within(cp, opt.side_search_radius).empty()) return;
    const FitTolerance tol = fitToleranceAt(cp);
    // The pattern of n blobs (slots given) at `pose`, with weak peaks in its
    // missing slots; at least `min_n` blobs in all.
    auto tryPattern = [&](const int* blob, const int* slot, int n, const PatternPose& pose, int min_n) {
      unsigned filled = 0;
      for (int i = 0; i < n; ++i) filled |= 1u << slot[i];
      int found[kPatternSlots];
      double error[kPatternSlots];
      FitTolerance weak_tol = tol;
      weak_tol.mm = opt.weak_side_tolerance;
      const int n_weak = findWeakSlots(pose, filled, weak_index, weak_tol, found, error);
      if (n_weak == 0 || n + n_weak < min_n) return;
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
      h.rank = h.pose.score * (h.n == kPatternSlots ? 1.0 : kFourBlobPenalty) * (1 - kWeakSideRankStep * n_weak);
      if (h.rank > best.rank) best = h;
    };
    auto onRing = [&](const FieldMm& p) {
      return std::abs(dist(p, cp) - RobotPatternGeometry::kSideBlobDistance) <= kWeakPairRingTolerance;
    };
    if (best.rank > 0 && best.n == kPatternSlots - 1)
      tryPattern(best.blob, best.slot, best.n, best.pose, kPatternSlots);
    if (best.rank > 0 && best.n == kPatternSlots) return;
    // Two side blobs: on the ring, as far apart in angle as two slots.
    forSideBlobPairs(c, nbr, k, [&](const int* blob, const int* slot, const PatternPose& pose) {
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
  }

  // Whether the blob of `slot` at `pose` (on the search plane) cannot be
  // seen whole: part of its disc lies outside the image.
  bool slotOutOfView(const PatternPose& pose, int slot) const {
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

  // Whether the frame shows a side marker at `slot` of `pose` where no peak
  // was found: the color read there (seen_color.h), in full view, is at
  // least kMarkerBrightness as bright as the center blob `c` (a dark
  // color's chromaticity is unreliable, and the robot top is dark), at
  // least kOverCarpet as bright as the carpet just beyond the robot's rim
  // in the same direction where that reads as carpet rather than a line (a
  // green dot has the carpet's chromaticity; the slots of a pattern made of
  // clutter lie on the carpet), and clearly
  // nearer to the green or the pink class than to the other.
  bool slotShowsMarker(const PatternPose& pose, int slot, int c) const {
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
  void completeFromTwoSides(int c, const int* nbr, int k, Hypothesis& best) {
    // Reading the frame costs: only for a center that looks like a team
    // color rather than a side color (a side blob is a center candidate too).
    auto nearer = [&](int a, int b) {
      return std::min(colorDistance(blobs[c].color, classes[a].color), colorDistance(blobs[c].color, classes[b].color));
    };
    const bool center_like = nearer(kYellow, kBlue) < nearer(kGreen, kPink);
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
    if (best.rank > 0 || weak_index.points().empty()) return;
    std::array<int, 64> mixed;
    int m = 0;
    for (int i = 0; i < k; ++i) mixed[m++] = nbr[i];
    const int n_blobs = m;
    for (const auto& hit : weak_index.within(blobs[c].at_ref, opt.side_search_radius)) {
      if (m == static_cast<int>(mixed.size())) break;
      const int w = n_strong + static_cast<int>(hit.first);
      if (hit.second >= sq(kMinSideDistance) && brightness(w) >= kTopBrightness * brightness(c))
        mixed[m++] = w;
    }
    if (m == n_blobs) return;
    forSideBlobPairs(c, mixed.data(), m, [&](const int* blob, const int* slot, const PatternPose& pose) {
      if (blobs[blob[1]].weak != blobs[blob[2]].weak) take(blob, slot, pose);
    });
  }

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

  bool overlapsAccepted(const PatternPose& pose, const Hypothesis* skip = nullptr) const {
    for (const auto& r : robots) {
      if (&r == skip) continue;
      if (robotTopsOverlap(pose.position, pose.orientation, r.pose.position, r.pose.orientation))
        return true;
    }
    return false;
  }

  void selectRobots() {
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

  // ------------------------------------------------------ color classes
  // Clutter (carpet noise, line crossings) can line up like a pattern. A
  // robot's center must look like this frame's yellow or blue rather than
  // like the field or a white line; the team colors come from clustering
  // the centers first, so no fixed hue is involved.
  // Center blob colors of the robot hypotheses in two classes, yellow vs
  // blue, with green and pink as the external colors (eq. 5.24); the labels
  // are left in `labels`.
  TwoMeansResult clusterCenters() {
    samples.clear();
    for (const auto& r : robots) samples.push_back(blobs[r.blob[0]].color);
    labels.resize(samples.size());
    const ColorVec prior[2] = {classes[kYellow].color, classes[kBlue].color};
    const ColorVec ext[2] = {classes[kGreen].color, classes[kPink].color};
    return twoMeans(samples.data(), static_cast<int>(samples.size()), prior, ext, 2, labels.data());
  }

  // Drops the robots whose center looks like the field or a line more than
  // like its team's color, marks those centers implausible, and returns how
  // many were dropped.
  int dropImplausibleCenters() {
    const int nr = static_cast<int>(robots.size());
    if (nr == 0) return 0;
    const auto res = clusterCenters();
    int kept = 0;
    for (int i = 0; i < nr; ++i) {
      const ColorVec& c = samples[i];
      const float d_team = colorDistance(c, res.mean[labels[i]]);
      const float d_bg = std::min(colorDistance(c, classes[kField].color),
                                  colorDistance(c, classes[kWhite].color));
      if (d_bg < d_team) {
        for (int b = 0; b < robots[i].n; ++b) blobs[robots[i].blob[b]].robot = -1;
        blobs[robots[i].blob[0]].implausible_center = true;
        continue;
      }
      for (int b = 0; b < robots[i].n; ++b) blobs[robots[i].blob[b]].robot = kept;
      robots[kept++] = robots[i];
    }
    robots.resize(kept);
    return nr - kept;
  }

  void learnClass(int a, int b, const TwoMeansResult& r) {
    const float fp = static_cast<float>(opt.retention_force);
    const float fr = static_cast<float>(opt.reference_force);
    const int cls[2] = {a, b};
    for (int k = 0; k < 2; ++k) {
      if (r.count[k] > 0) {
        frame_seen[cls[k]] = true;
        frame_color[cls[k]] = r.mean[k];
        classes[cls[k]].update(r.mean[k], fp, fr);
      }
    }
  }

  void classifyRobots() {
    for (int k = 0; k < kNumClasses; ++k) frame_color[k] = classes[k].color, frame_seen[k] = false;
    const int nr = static_cast<int>(robots.size());
    if (nr == 0) return;

    // Teams: center blobs, yellow vs blue; green and pink are external.
    {
      const auto res = clusterCenters();
      for (int i = 0; i < nr; ++i) robots[i].team = labels[i] == 0 ? Team::Yellow : Team::Blue;
      learnClass(kYellow, kBlue, res);
    }

    // Side blobs of all robots: green vs pink; the team colors are external.
    // Weak peaks' colors are too noisy to learn from.
    samples.clear();
    for (const auto& r : robots)
      for (int i = 1; i < r.n; ++i)
        if (!blobs[r.blob[i]].weak) samples.push_back(blobs[r.blob[i]].color);
    labels.resize(samples.size());
    {
      const ColorVec prior[2] = {classes[kGreen].color, classes[kPink].color};
      const ColorVec ext[2] = {frame_color[kYellow], frame_color[kBlue]};
      const auto res =
          twoMeans(samples.data(), static_cast<int>(samples.size()), prior, ext, 2, labels.data());
      // This frame's side colors seed the per-robot clustering.
      const ColorVec green = res.count[0] > 0 ? res.mean[0] : classes[kGreen].color;
      const ColorVec pink = res.count[1] > 0 ? res.mean[1] : classes[kPink].color;
      learnClass(kGreen, kPink, res);
      frame_color[kGreen] = green;
      frame_color[kPink] = pink;
    }

    // Per robot: its own side blobs, against its own center color; then its
    // weak sides by the nearer of its own two side colors (or the frame's
    // where it shows one only), when clearly nearer.
    for (auto& r : robots) {
      ColorVec local[4];
      uint8_t lab[4];
      int side_of[4];
      int m = 0;
      for (int i = 1; i < r.n; ++i)
        if (!blobs[r.blob[i]].weak) side_of[m] = i, local[m++] = blobs[r.blob[i]].color;
      const ColorVec prior[2] = {frame_color[kGreen], frame_color[kPink]};
      const ColorVec ext[1] = {blobs[r.blob[0]].color};
      const TwoMeansResult res = twoMeans(local, m, prior, ext, 1, lab);
      std::array<MarkerColor, 4> colors;
      colors.fill(MarkerColor::Green);  // a missing side blob is guessed green
      r.seen_sides = 0;
      for (int i = 0; i < m; ++i) {
        const int slot = r.slot[side_of[i]];
        colors[slot - 1] = lab[i] == 0 ? MarkerColor::Green : MarkerColor::Pink;
        r.seen_sides |= static_cast<uint8_t>(1u << (slot - 1));
      }
      const ColorVec green = res.count[0] > 0 ? res.mean[0] : frame_color[kGreen];
      const ColorVec pink = res.count[1] > 0 ? res.mean[1] : frame_color[kPink];
      for (int i = 1; i < r.n; ++i) {
        if (!blobs[r.blob[i]].weak) continue;
        const int label = weakSideColor(blobs[r.blob[i]].color, green, pink,
                                        static_cast<float>(opt.weak_color_margin));
        if (label < 0) continue;
        colors[r.slot[i] - 1] = label == 0 ? MarkerColor::Green : MarkerColor::Pink;
        r.seen_sides |= static_cast<uint8_t>(1u << (r.slot[i] - 1));
      }
      if (r.seen_sides != 0xF) probeMissingSides(r, green, pink, colors);
      r.colors = colors;
      r.id = patternId(colors);
    }
    // A robot missing side blobs has two (one missing) or four (two, at the
    // image border) possible ids; ids are unique per team, so the ids fully
    // seen teammates hold are ruled out. The guess is the first one left,
    // the missing blobs taken as green before pink; the id is known when
    // one is left.
    for (auto& r : robots) {
      r.id_known = r.fullPattern();
      if (r.fullPattern()) continue;
      int missing[4], m = 0;
      for (int s = 0; s < 4; ++s)
        if (!(r.seen_sides >> s & 1)) missing[m++] = s;
      auto taken = [&](int id) {
        for (const auto& o : robots)
          if (&o != &r && o.fullPattern() && o.team == r.team && o.id == id) return true;
        return false;
      };
      int free = 0;
      std::array<MarkerColor, 4> guess = r.colors;
      for (int pinks = 0; pinks < (1 << m); ++pinks) {
        auto c = r.colors;
        for (int i = 0; i < m; ++i) c[missing[i]] = pinks >> i & 1 ? MarkerColor::Pink : MarkerColor::Green;
        if (taken(patternId(c))) continue;
        if (free++ == 0) guess = c;
      }
      r.colors = guess;
      r.id = patternId(guess);
      r.id_known = free == 1;
    }

    // How this camera shows the pattern colors tells where its orange is.
    ColorVec ref[4], seen[4];
    int n = 0;
    for (int k : {kYellow, kBlue, kGreen, kPink})
      if (frame_seen[k]) ref[n] = classes[k].reference, seen[n] = frame_color[k], ++n;
    color_map.fit(ref, seen, n);
  }

  // The side slots of `r` that neither a blob nor a weak peak filled: the
  // color the camera saw there (seen_color.h), when clearly nearer to the
  // robot's own `green` or `pink`, sets the slot's marker.
  void probeMissingSides(Hypothesis& r, const ColorVec& green, const ColorVec& pink,
                         std::array<MarkerColor, 4>& colors) const {
    if (!opt.probe_missing_sides || !frame_view.image) return;
    Hypothesis at_team = r;
    refit(at_team);
    const double z = teamHeight(r.team);
    for (int s = 1; s < kPatternSlots; ++s) {
      if (r.seen_sides >> (s - 1) & 1) continue;
      const FieldMm p = slotPosition(at_team.pose.position, at_team.pose.orientation, s);
      const SeenColor seen = seenDiscColor(frame_view, camera, {p.x, p.y, z}, opt.probe_radius);
      if (seen.share < opt.min_probe_share) continue;
      const int label = weakSideColor(colorFeature(seen.rgb[0], seen.rgb[1], seen.rgb[2]), green, pink,
                                      static_cast<float>(opt.weak_color_margin));
      if (label < 0) continue;
      colors[s - 1] = label == 0 ? MarkerColor::Green : MarkerColor::Pink;
      r.seen_sides |= static_cast<uint8_t>(1u << (s - 1));
    }
  }

  // Refit at the team's height (pattern offsets are mm on the robot top).
  // Weak peaks sit less exactly than blobs: where the center and three side
  // blobs are blobs, those alone give the pose.
  void refit(Hypothesis& h) const {
    FieldMm pts[kPatternSlots];
    int slots[kPatternSlots];
    const int t = h.team == Team::Yellow ? 0 : 1;
    const bool blobs_only = weakCount(h) > 0 && h.n - weakCount(h) >= kPatternSlots - 1;
    int n = 0;
    for (int i = 0; i < h.n; ++i) {
      if (blobs_only && blobs[h.blob[i]].weak) continue;
      pts[n] = blobs[h.blob[i]].at_team[t];
      slots[n++] = h.slot[i];
    }
    h.pose = fitPattern(pts, slots, n, opt.score_scale);
  }

  int weakCount(const Hypothesis& h) const {
    int n = 0;
    for (int i = 0; i < h.n; ++i) n += blobs[h.blob[i]].weak;
    return n;
  }

  int nearestOf(const ColorVec& c, int a, int b) const {
    return colorDistance(c, frame_color[a]) <= colorDistance(c, frame_color[b]) ? a : b;
  }

  // ----------------------------------------------------------- tracking
  void predictTracks(double t) {
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

  void associateTracks() {
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

  // A track that found no full pattern: look for two or more of its blobs
  // around the predicted blob positions (§5.3.6), colors agreeing with its
  // identity.
  void recoverTrack(int k) {
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

  void updateTrack(RobotTrack& tr, const Hypothesis& h, double t) {
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

  // Identity hysteresis: a tracked robot keeps team and id until several
  // consecutive frames agree on the same different identity.
  void applyIdentity(RobotTrack& tr, Hypothesis& h) {
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

  // A frame that shares few of its robots with the tracks shows an unrelated
  // scene (independent images played as a sequence): a frame that follows
  // the last one re-finds nearly every robot near its prediction, while a
  // new scene meets old tracks only by chance. A dark or occluded frame has
  // few fresh robots, and those it has still meet their tracks.
  bool unrelatedToTracks() const {
    const int fresh = static_cast<int>(robots.size()), known = static_cast<int>(tracks.size());
    const int fewer = std::min(fresh, known);
    if (fewer < kSceneCheckMinRobots) return false;
    int associated = 0;
    for (int k : track_match) associated += k >= 0;
    return 2 * associated < fewer;
  }

  void track(double t) {
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

  // --------------------------------------------------------------- balls
  void findBalls(double t, bool tracking, Detections& out) {
    ball_cands.clear();
    // Learned negatives: everything a ball candidate must be farther from
    // than from the orange class.
    const int negatives[] = {kField, kWhite, kPink, kGreen, kYellow, kBlue};
    const ColorVec orange = classes[kOrange].color;
    const ColorVec mapped_orange = color_map.apply(classes[kOrange].reference);
    // Strength reference: the median score of this frame's robot blobs.
    score_buf.clear();
    for (const auto& r : robots)
      for (int i = 0; i < r.n; ++i)
        if (!blobs[r.blob[i]].weak) score_buf.push_back(blobs[r.blob[i]].score);
    double strength_ref = 0;
    if (!score_buf.empty()) {
      auto mid = score_buf.begin() + score_buf.size() / 2;
      std::nth_element(score_buf.begin(), mid, score_buf.end());
      strength_ref = *mid;
    }
    // Ball predictions: straight on from the last two frames, mirrored at
    // the walls it would cross.
    for (auto& bt : ball_tracks) {
      bt.predicted = bt.pos[1];
      const double dt = std::max(0.0, t - bt.t[1]);
      const double reach = opt.max_ball_speed * std::min(dt, 0.1);
      if (bt.history >= 2 && bt.t[1] > bt.t[0]) {
        const double f = dt / (bt.t[1] - bt.t[0]);
        bt.predicted = reflectAtWalls(bt.pos[1], {bt.pos[1].x + f * (bt.pos[1].x - bt.pos[0].x),
                                       bt.pos[1].y + f * (bt.pos[1].y - bt.pos[0].y)});
        bt.gate = 30 + 0.5 * reach;
      } else {
        bt.gate = 30 + reach;
      }
      // Next to a robot the ball may have been kicked in any direction: the
      // track also takes what it could reach from its last position.
      bt.kick_gate = 0;
      const double touch = RobotPatternGeometry::kMaxRadius + opt.ball_radius +
                           (opt.max_ball_speed + opt.max_robot_speed) * std::min(dt, 0.1);
      for (const auto& r : robots)
        if (dist(bt.pos[1], r.pose.position) < touch) bt.kick_gate = 30 + reach;
      bt.confirmed = false;
    }
    const double keep_out = minBallOutsideDistance(opt.ball_radius);
    ColorVec field_sum;
    int field_n = 0;
    const double margin = 50;
    for (int i = 0; i < n_strong; ++i) {  // never a weak peak
      const FrameBlob& b = blobs[i];
      if (!b.valid || b.robot >= 0) continue;
      const FieldMm p = b.at_ball;
      if (p.x < ball_area.x_min - margin || p.x > ball_area.x_max + margin ||
          p.y < ball_area.y_min - margin || p.y > ball_area.y_max + margin)
        continue;
      // Against every class, the blob counts with the colors it may have
      // had before a channel clipped (an overexposed ball looks yellowish).
      const ClippedColor seen(b.rgb);
      if (seen.saturated()) continue;
      // A streak is the object's color mixed with the carpet it crossed:
      // it is compared with each class's mixing line from the field color.
      const ColorVec& field_color = frame_color[kField];
      auto classDistance = [&](const ColorVec& c) {
        return b.streak ? streakColorDistance(seen, field_color, c) : seen.distance(c);
      };
      float d_or = classDistance(orange);
      if (color_map.valid()) d_or = std::min(d_or, classDistance(mapped_orange));
      float d_neg = std::numeric_limits<float>::max();
      int nearest_neg = kField;
      for (int k : negatives) {
        const float d = k == kField ? seen.distance(field_color) : classDistance(frame_color[k]);
        if (d < d_neg) d_neg = d, nearest_neg = k;
      }
      if (d_or >= d_neg) {
        if (nearest_neg == kField && !b.streak) {
          for (int c = 0; c < 3; ++c) field_sum.c[c] += b.color.c[c];
          ++field_n;
        }
        continue;
      }
      // Rules: at least 80 % of the ball is outside every robot's top.
      bool inside = false;
      for (const auto& r : robots) {
        if (dist(p, r.pose.position) > RobotPatternGeometry::kTopRadius + keep_out) continue;
        if (distanceToRobotTop(p, r.pose.position, r.pose.orientation) < keep_out) {
          inside = true;
          break;
        }
      }
      if (inside) continue;
      const double margin_ratio = (d_neg - d_or) / (d_neg + d_or);
      const double color_conf = std::min(1.0, margin_ratio / 0.3);
      // A streak's score is a shape measure of its own scale (streak_score.h).
      const double strength =
          b.streak ? std::min(1.0, b.score / kStreakFullStrength)
                   : (strength_ref > 0 ? std::min(1.0, b.score / (0.4 * strength_ref)) : 1.0);
      BallCandidate c;
      c.blob = i;
      c.pos = p;
      double temporal = 1.0;
      if (tracking && have_frame && !new_scene) {
        temporal = 0.85;
        double best = std::numeric_limits<double>::max();
        for (size_t k = 0; k < ball_tracks.size(); ++k) {
          const BallTrack& bt = ball_tracks[k];
          double d = dist(p, bt.predicted);
          if (d >= bt.gate) {
            // Kicked: ranked behind any candidate on the predicted course.
            const double from_last = dist(p, bt.pos[1]);
            if (from_last >= bt.kick_gate) continue;
            d = bt.gate + from_last;
          }
          if (d < best) best = d, c.track = static_cast<int>(k);
        }
        if (c.track >= 0) temporal = 1.0;
      }
      c.confidence = color_conf * strength * temporal;
      if (c.confidence >= opt.min_ball_confidence) ball_cands.push_back(c);
    }
    std::sort(ball_cands.begin(), ball_cands.end(),
              [](const BallCandidate& a, const BallCandidate& b) { return a.confidence > b.confidence; });
    // One ball per place: weaker candidates within a ball diameter go.
    int kept = 0;
    for (size_t i = 0; i < ball_cands.size(); ++i) {
      bool dup = false;
      for (int j = 0; j < kept && !dup; ++j)
        dup = dist(ball_cands[i].pos, ball_cands[j].pos) < 4 * opt.ball_radius;
      if (!dup && kept < opt.max_balls) ball_cands[kept++] = ball_cands[i];
    }
    ball_cands.resize(kept);
    // A streak is trusted where it continues a ball track (on its course or
    // kicked from a robot) or where nothing else in the frame is a ball: a
    // colored region that stands out is weaker evidence than a round blob.
    bool round_ball = false;
    for (const auto& c : ball_cands) round_ball |= !blobs[c.blob].streak;
    if (round_ball) {
      ball_cands.erase(std::remove_if(ball_cands.begin(), ball_cands.end(),
                                      [&](const BallCandidate& c) { return blobs[c.blob].streak && c.track < 0; }),
                       ball_cands.end());
    }

    // Learn orange from a convincing ball, the field from the clutter.
    const float fp = static_cast<float>(opt.retention_force);
    const float fr = static_cast<float>(opt.reference_force);
    // (A streak's color is diluted by the carpet it passed over.)
    if (!ball_cands.empty() && ball_cands[0].confidence >= 0.5 && !blobs[ball_cands[0].blob].streak)
      classes[kOrange].update(blobs[ball_cands[0].blob].color, fp, fr);
    if (field_n > 0) {
      for (int c = 0; c < 3; ++c) field_sum.c[c] /= field_n;
      classes[kField].update(field_sum, fp, fr);
    }

    if (tracking) {
      for (auto& c : ball_cands) {
        if (c.track >= 0 && !ball_tracks[c.track].confirmed) {
          BallTrack& bt = ball_tracks[c.track];
          bt.pos[0] = bt.pos[1];
          bt.t[0] = bt.t[1];
          bt.pos[1] = c.pos;
          bt.t[1] = t;
          bt.history = 2;
          ++bt.hits;
          bt.confirmed = true;
        } else {
          c.track = -1;
        }
      }
      // Unconfirmed ball tracks survive a short gap (flicker, occlusion).
      ball_tracks.erase(std::remove_if(ball_tracks.begin(), ball_tracks.end(),
                                       [&](const BallTrack& bt) {
                                         return !bt.confirmed && t - bt.t[1] > 0.1;
                                       }),
                        ball_tracks.end());
      for (const auto& c : ball_cands) {
        if (c.track >= 0 || ball_tracks.size() >= 16) continue;
        BallTrack bt;
        bt.pos[1] = c.pos;
        bt.t[1] = t;
        bt.history = 1;
        bt.hits = 1;
        bt.confirmed = true;
        ball_tracks.push_back(bt);
      }
    }

    const double plane = plane_height;
    for (const auto& c : ball_cands) {
      BallDetection d;
      d.confidence = static_cast<float>(std::clamp(c.confidence, 0.0, 1.0));
      const FieldMm at_plane = raw_positions[c.blob];
      const auto px = camera.fieldToImage({at_plane.x, at_plane.y, plane});
      std::optional<FieldPoint> fp3;
      if (px) fp3 = camera.imageToField(*px, opt.ball_radius);
      d.position = fp3 ? FieldPoint{fp3->x, fp3->y, opt.ball_radius}
                       : FieldPoint{c.pos.x, c.pos.y, opt.ball_radius};
      if (px) d.pixel = *px;
      out.balls.push_back(d);
    }
  }

  std::vector<FieldMm> raw_positions;
  double plane_height = 150;

  FrameView frame_view;  // the frame being processed (may be empty)

  void process(const BlobList& list, double t, Detections& out, const FrameView& frame) {
    frame_view = frame;
    out.balls.clear();
    out.robots.clear();
    // Time going backwards or a long gap: the frames are unrelated.
    new_scene = have_frame && (t <= last_t || t - last_t > 0.5);
    if (new_scene) {
      tracks.clear();
      ball_tracks.clear();
    }
    plane_height = list.plane_height;
    raw_positions.clear();
    for (const Blob& b : list.blobs) raw_positions.push_back(b.position);
    prepare(list);
    findHypotheses();
    // A hypothesis around a side blob taken for a center can hold a real
    // robot's blobs until its center is found implausible; the robots it
    // blocked get a second chance.
    selectRobots();
    if (dropImplausibleCenters() > 0) {
      selectRobots();
      dropImplausibleCenters();
    }
    classifyRobots();
    for (auto& r : robots) {
      if (opt.robot_height_yellow != opt.robot_height_blue || weakCount(r) > 0) refit(r);
    }
    if (opt.tracking) {
      if (!have_frame) tracks.clear();
      track(t);
    }
    findBalls(t, opt.tracking, out);

    for (const auto& r : robots) {
      // The league's protocol has no unknown id, and a wrong one counts as
      // a false robot and a missed one: a guessed id is not reported.
      if (!r.id_known && !opt.report_guessed_ids) continue;
      // A robot cut by the image border (two side blobs) is reported only
      // with a known id: the frame, a track or the teammates must tell it.
      if (!r.id_known && r.n < kPatternSlots - 1) continue;
      RobotDetection d;
      d.team = r.team;
      d.id = r.id;
      d.height = teamHeight(r.team);
      d.orientation = r.pose.orientation;
      d.confidence = static_cast<float>(std::clamp(r.confidence, 0.0, 1.0));
      const auto px = camera.fieldToImage({r.pose.position.x, r.pose.position.y, d.height});
      d.position = r.pose.position;
      if (px) {
        d.pixel = *px;
        if (const auto back = camera.imageToField(*px, d.height)) d.position = back->xy();
      }
      out.robots.push_back(d);
    }
    // std::sort: stable_sort may allocate a buffer.
    std::sort(out.robots.begin(), out.robots.end(),
              [](const RobotDetection& a, const RobotDetection& b) {
                if (a.confidence != b.confidence) return a.confidence > b.confidence;
                return a.position.x < b.position.x;
              });
    last_t = t;
    have_frame = true;
  }
};

void validateDetectorOptions(const DetectorOptions& o, const CameraModel& camera) {
  auto fail = [](const std::string& what) { throw InputError("detector options", what); };
  auto positive = [&](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) fail(std::string(name) + " must be > 0, got " + std::to_string(v));
  };
  positive(o.robot_height_yellow, "robot_height_yellow");
  positive(o.robot_height_blue, "robot_height_blue");
  positive(o.ball_radius, "ball_radius");
  positive(o.side_search_radius, "side_search_radius");
  positive(o.score_scale, "score_scale");
  positive(o.max_robot_acceleration, "max_robot_acceleration");
  positive(o.max_prediction_dt, "max_prediction_dt");
  positive(o.min_uncertainty, "min_uncertainty");
  positive(o.track_gate, "track_gate");
  positive(o.max_robot_speed, "max_robot_speed");
  positive(o.max_ball_speed, "max_ball_speed");
  if (!(o.retention_force >= 0 && o.reference_force >= 0 &&
        o.retention_force + o.reference_force <= 1))
    fail("retention_force and reference_force must be >= 0 with a sum <= 1, got " +
         std::to_string(o.retention_force) + " and " + std::to_string(o.reference_force));
  if (!(o.min_robot_score >= 0 && o.min_robot_score < 1))
    fail("min_robot_score must be in [0, 1), got " + std::to_string(o.min_robot_score));
  positive(o.probe_radius, "probe_radius");
  if (!(o.min_probe_share > 0 && o.min_probe_share <= 1))
    fail("min_probe_share must be in (0, 1], got " + std::to_string(o.min_probe_share));
  if (o.min_side_blobs < 3 || o.min_side_blobs > 4)
    fail("min_side_blobs must be 3 or 4, got " + std::to_string(o.min_side_blobs));
  if (o.identity_switch_frames < 1)
    fail("identity_switch_frames must be >= 1, got " + std::to_string(o.identity_switch_frames));
  if (o.max_balls < 0) fail("max_balls must be >= 0, got " + std::to_string(o.max_balls));
  const double cz = camera.position().z();
  if (o.robot_height_yellow >= cz || o.robot_height_blue >= cz)
    fail("robot heights must lie below the camera (" + std::to_string(cz) + " mm)");
}

Detector::Detector(const CameraModel& camera, const FieldModel& field, const DetectorOptions& opt)
    : opt_(opt) {
  validateDetectorOptions(opt, camera);
  impl_ = std::make_unique<Impl>(camera, field, opt);
}
Detector::~Detector() = default;
Detector::Detector(Detector&&) noexcept = default;
Detector& Detector::operator=(Detector&&) noexcept = default;

void Detector::reset() { impl_->reset(); }

Detector::ColorSeparations Detector::colorSeparations() const {
  const auto& c = impl_->classes;
  return {colorDistance(c[kYellow].color, c[kBlue].color), colorDistance(c[kGreen].color, c[kPink].color),
          colorDistance(c[kOrange].color, c[kField].color)};
}

const char* Detector::classColorName(int i) {
  static const char* kNames[kNumClasses] = {"yellow", "blue", "green", "pink", "orange", "field", "white"};
  return i >= 0 && i < kNumClasses ? kNames[i] : "";
}

void Detector::classColors(ColorVec out[kClassColorCount]) const {
  static_assert(kClassColorCount == kNumClasses, "one name per class");
  for (int i = 0; i < kNumClasses; ++i) out[i] = impl_->classes[i].color;
}

void Detector::setOptions(const DetectorOptions& opt) {
  validateDetectorOptions(opt, impl_->camera);
  opt_ = opt;
  impl_->setOptions(opt);
}

void Detector::process(const BlobList& blobs, double t_capture, Detections& out, const FrameView& frame) {
  impl_->process(blobs, t_capture, out, frame);
}

}  // namespace dv

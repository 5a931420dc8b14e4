#include "detection/detector_impl.h"

#include "detection/marker_colored_ball.h"
#include "detection/seen_color.h"
#include "geometry/robot_pattern.h"

namespace dv {

Detector::Impl::Impl(const CameraModel& cam, const FieldModel& f, const DetectorOptions& o)
    : camera(cam), field(f), opt(o), cam_pos(cam.position()), search(cam) {
  ball_area = field.withBoundary();
  setOptions(o);
  blobs.reserve(4096);
  streak_blobs.reserve(4096);
  hyps.reserve(1024);
  robots.reserve(64);
  robot_positions.reserve(64);
  ball_cands.reserve(1024);
  marker_colored.reserve(1024);
  border_balls.reserve(64);
  pale.reserve(BlobList::kMaxPale);
  samples.reserve(512);
  labels.reserve(512);
  sample_rgb.reserve(512);
  center_labels.reserve(512);
  score_buf.reserve(512);
  reset();
}

void Detector::Impl::setOptions(const DetectorOptions& o) {
  opt = o;
  tracker.setOptions(RobotTrackerOptions::from(o));
  ball_tracker.setOptions({field.withBoundary(), o.ball_radius, o.max_ball_speed, o.max_robot_speed});
  fast_streaks.setLimits(o.max_robot_speed, o.max_ball_speed, o.ball_radius);
  ref_height = 0.5 * (opt.robot_height_yellow + opt.robot_height_blue);
  search.setOptions(o, ref_height, ball_area);
  const ColorRef* refs[kNumClasses] = {&opt.ref_yellow, &opt.ref_blue,   &opt.ref_green,
                                       &opt.ref_pink,   &opt.ref_orange, &opt.ref_field,
                                       &opt.ref_white};
  for (int k = 0; k < kNumClasses; ++k) classes[k].reference = feature(*refs[k]);
  if (!border_finder || border_finder->ballRadius() != opt.ball_radius)
    border_finder.emplace(camera, field.withBoundary(), opt.ball_radius);
}

void Detector::Impl::reset() {
  for (auto& c : classes) c.reset();
  color_map.reset();
  tracker.clear();
  ball_tracker.clear();
  fast_streaks.clear();
  have_frame = false;
}

void Detector::Impl::prepare(const BlobList& list) {
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
    if (!weak && !b.streak && f.valid) readUnclipped(b, z0, f);
    blobs.push_back(f);
    // Invalid blobs and streaks are put far away so that no query finds them.
    (weak ? weak_pts : pts).push_back(f.valid && !f.streak ? f.at_ref : FieldMm{1e12, 1e12});
  }
  index.build();
  if (!weak_pts.empty()) weak_index.build();
}

void Detector::Impl::readUnclipped(const Blob& b, double z0, FrameBlob& f) const {
  const ClippedColor clipped(b.rgb);
  if (!clipped.saturated()) return;
  const auto px = camera.fieldToImage({b.position.x, b.position.y, z0});
  if (!px) return;
  // Within the smallest of the dots and the ball.
  const double radius = std::min(RobotPatternGeometry::kSideBlobRadius, opt.ball_radius);
  const FieldPoint at{b.position.x, b.position.y, z0};
  SeenColor rim = unclippedDiscColor(frame_view, *px, ballRadiusPx(camera, at, radius));
  // Clipped in two channels all over that disc, a ball in a sun patch has
  // its unclipped rim in its blurred edge: read out to midway between its
  // radius and the ring that must show carpet (a three-channel clip is a
  // center's, read by its rim against the robot's top: readByRim).
  if (!(rim.share > 0) && !clipped.white())
    rim = unclippedDiscColor(frame_view, *px, ballRadiusPx(camera, at, (opt.ball_radius + kCarpetRingMm) / 2));
  if (!(rim.share > 0) || ClippedColor(rim.rgb).saturated()) return;
  f.has_unclipped = true;
  std::copy(rim.rgb, rim.rgb + 3, f.unclipped_rgb);
}

void Detector::Impl::process(const BlobList& list, double t, Detections& out, const FrameView& frame) {
  frame_view = frame;
  out.balls.clear();
  out.robots.clear();
  // Time going backwards or a long gap: the frames are unrelated.
  new_scene = have_frame && (t <= last_t || t - last_t > 0.5);
  if (new_scene) {
    tracker.clear();
    ball_tracker.clear();
    fast_streaks.clear();
  }
  plane_height = list.plane_height;
  health = {};
  // White is what the lines show in this frame, never a fixed color.
  neutral = list.neutral;
  carpet = list.carpet;
  min_saturation = list.min_saturation;
  if (neutral.valid) {
    classes[kWhite].color = colorFeature(neutral.rgb[0], neutral.rgb[1], neutral.rgb[2]);
  } else {
    classes[kWhite].reset();
  }
  pale.assign(list.pale.begin(), list.pale.end());
  raw_positions.clear();
  for (const Blob& b : list.blobs) raw_positions.push_back(b.position);
  for (const Blob& b : list.weak) raw_positions.push_back(b.position);
  prepare(list);
  ColorVec class_colors[kNumClasses];
  for (int k = 0; k < kNumClasses; ++k) class_colors[k] = classes[k].color;
  search.find(searchInputs(class_colors), hyps);
  // A hypothesis around a side blob taken for a center can hold a real
  // robot's blobs until its center is found implausible; the robots it
  // blocked get a second chance.
  selectRobots();
  if (dropImplausibleCenters() > 0) {
    selectRobots();
    dropImplausibleCenters();
  }
  learnFrameColors();
  dropDotsTakenForCenters();
  searchAgainWithFrameColors();
  learnUnseenTeam();
  robotsAroundUnpeakedCenters();
  robotsAroundLoneSides();
  dropCentersAloneAtCrossings();
  identifyRobots();
  for (auto& r : robots) {
    if (opt.robot_height_yellow != opt.robot_height_blue || weakCount(r) > 0) refit(r);
  }
  if (opt.tracking) {
    if (!have_frame) tracker.clear();
    track(t);
  }
  dropSecondIds();
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
  for (const auto& r : out.robots) ++(r.team == Team::Yellow ? health.yellow : health.blue);
  health.balls = static_cast<int>(out.balls.size());
  health.yellow_blue = colorDistance(classes[kYellow].color, classes[kBlue].color);
  health.green_pink = colorDistance(classes[kGreen].color, classes[kPink].color);
  health.lines = neutral;
  frame_interval = have_frame && !new_scene ? t - last_t : 0;
  last_t = t;
  have_frame = true;
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

int Detector::Impl::searchAgainWithFrameColors() {
  bool learned = false;
  for (bool seen : frame_seen) learned = learned || seen;
  if (!learned) return 0;  // the same colors the first search had
  const HypothesisInputs in = searchInputs(frame_color);
  int added = 0;
  // A peaked marker of a robot's side: a blob, not a weak peak, green or
  // pink (under a cast the carpet may peak, and look like a team color).
  auto sideBlob = [&](int i) {
    const FrameBlob& s = blobs[i];
    return s.valid && !s.weak && !s.streak && sideColored(ClippedColor(s.rgb));
  };
  auto tryCenter = [&](int c, bool weak_center) {
    const FrameBlob& b = blobs[c];
    if (!b.valid || b.streak || b.robot >= 0 || b.implausible_center) return;
    Team team;
    if (!teamColored(ClippedColor(b.rgb), &team)) return;
    Hypothesis h = search.bestAt(in, c);
    if (h.rank <= 0 || overlapsAccepted(h.pose)) return;
    bool free = true, side_blob = false, weak_side = false;
    for (int i = 0; i < h.n && free; ++i) free = blobs[h.blob[i]].robot < 0;
    for (int i = 1; i < h.n; ++i) {
      side_blob = side_blob || sideBlob(h.blob[i]);
      weak_side = weak_side || blobs[h.blob[i]].weak;
    }
    if (!free || (weak_center && (!side_blob || weak_side))) return;
    h.team = team;
    h.confidence = h.rank;
    for (int i = 0; i < h.n; ++i) blobs[h.blob[i]].robot = static_cast<int>(robots.size());
    robots.push_back(h);
    ++added;
  };
  for (int c = 0; c < n_strong; ++c) tryCenter(c, false);
  // A weak peak as the center, beside a free side blob on the ring: a far
  // robot's center of a few pixels, dim under a cast, may peak below the
  // threshold where a side dot of it peaked. The pattern must hold such a
  // side blob and no other weak peak: the frame's reading alone around a
  // weak peak is too little, and two weak peaks line up by chance (under
  // a cold cast a blue-green carpet's texture peaks weakly, reads as sky
  // blue and its darker patches as teal blobs: a false robot of a weak
  // center, one such blob and a weak side).
  const double ring = RobotPatternGeometry::kSideBlobDistance;
  const double ring_tolerance = HypothesisSearch::kWeakPairRingTolerance;
  const int n_weak = static_cast<int>(weak_index.points().size());
  for (int w = 0; w < n_weak; ++w) {
    const int c = n_strong + w;
    bool beside = false;
    for (const auto& hit : index.within(blobs[c].at_ref, ring + ring_tolerance)) {
      const int i = static_cast<int>(hit.first);
      beside = beside || (blobs[i].robot < 0 && std::sqrt(hit.second) >= ring - ring_tolerance && sideBlob(i));
    }
    if (beside) tryCenter(c, true);
  }
  return added;
}

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

const DetectionHealth& Detector::health() const { return impl_->health; }

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

void Detector::Impl::expectedBalls(ExpectedPlaces& out) const {
  out.n = 0;
  if (!opt.tracking || !have_frame || !(frame_interval > 0)) return;
  FieldMm at_ball[ExpectedPlaces::kMax];
  const int n = ball_tracker.expectedFastBalls(last_t + frame_interval, at_ball, ExpectedPlaces::kMax);
  // Only where a ball can be (a prediction from two frames a moment apart
  // may reach far beyond).
  for (int k = 0; k < n; ++k)
    if (ball_area.contains(at_ball[k]) && alongRay(at_ball[k], opt.ball_radius, plane_height, out.at[out.n])) ++out.n;
}

void Detector::expectedBalls(ExpectedPlaces& out) const { impl_->expectedBalls(out); }

void Detector::process(const BlobList& blobs, double t_capture, Detections& out, const FrameView& frame) {
  impl_->process(blobs, t_capture, out, frame);
}

}  // namespace dv

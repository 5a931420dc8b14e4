#include <optional>

#include "detection/ball_policy.h"
#include "detection/ball_silhouette.h"
#include "detection/detector_impl.h"
#include "detection/marker_colored_ball.h"
#include "pipeline/view_stretch.h"

namespace dv {

namespace {

// How far a thin line's demosaiced false colors move its mix with the
// carpet: three of the least class radius (color_classes.h).
constexpr float kThinLineColorReach = 3 * kMinClassRadius;
// A border ball's strength: its fit's overlap (border_balls.h), full from
// that of a disc cut cleanly by a line with a pixel of blur.
constexpr double kBorderFullOverlap = 0.8;

// A round blob's strength: its score against a share of the frame's robot
// blobs' median score, unclamped (for ranking); 1 where no robot gives one.
constexpr double kBlobFullStrengthShare = 0.4;
double blobStrengthRatio(double score, double strength_ref) {
  return strength_ref > 0 ? score / (kBlobFullStrengthShare * strength_ref) : 1.0;
}
// The same, full from that share on.
double blobStrength(double score, double strength_ref) {
  return std::min(1.0, blobStrengthRatio(score, strength_ref));
}

}  // namespace

double Detector::Impl::ballTemporal(BallCandidate& c, bool tracking) {
  if (!tracking || !have_frame || new_scene) return 1.0;
  ball_tracker.match(c);
  return c.track >= 0 ? 1.0 : 0.85;
}

double Detector::Impl::courseConfidence(const BallCandidate& c) const {
  if (c.track < 0 || c.kicked) return 0;
  const BallTrack& bt = ball_tracker.tracks()[c.track];
  // Faster than any robot: nothing but a ball moves so (a robot's dot, a
  // robot not found, is not carpet either).
  if (!ball_tracker.isFast(bt)) return 0;
  return 1 - dist(c.pos, bt.predicted) / bt.gate;
}

void Detector::Impl::findBalls(double t, bool tracking, Detections& out) {
  ball_cands.clear();
  if (tracking) fast_streaks.begin(t);
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
  // A ball no class explains is at least as bright as a share of the
  // robots' center blobs (darker peaks lie on robot tops).
  score_buf.clear();
  for (const auto& r : robots) {
    const float* c = blobs[r.blob[0]].rgb;
    score_buf.push_back(c[0] + c[1] + c[2]);
  }
  float min_ball_brightness = std::numeric_limits<float>::max();
  if (!score_buf.empty()) {
    auto mid = score_buf.begin() + score_buf.size() / 2;
    std::nth_element(score_buf.begin(), mid, score_buf.end());
    min_ball_brightness = kTopBrightness * *mid;
  }
  robot_positions.clear();
  for (const auto& r : robots) robot_positions.push_back(r.pose.position);
  ball_tracker.predict(t, robot_positions.data(), static_cast<int>(robot_positions.size()));
  for (int k = 0; k < kNumClasses; ++k) {
    ball_colors.color[k] = frame_color[k];
    ball_colors.spread[k] = frame_spread[k];
    ball_colors.seen[k] = frame_seen[k];
  }
  ball_colors.color[kOrange] = classes[kOrange].color;
  ball_colors.white = neutral;
  ball_colors.yellow_hue_min = yellow_hue_min;
  ball_colors.mapped_orange.reset();
  if (color_map.valid()) ball_colors.mapped_orange = color_map.apply(classes[kOrange].reference);
  const ColorVec carpet_color = colorFeature(carpet.rgb[0], carpet.rgb[1], carpet.rgb[2]);
  ring_colors = ball_colors;
  if (carpet.valid) {
    ring_colors.color[kField] = carpet_color;
    ring_colors.seen[kField] = true;
  }
  const BallColorJudge judge(ball_colors, min_ball_brightness);
  const BallColorJudge judge_unfaded(ball_colors, min_ball_brightness, false);
  auto insideRobot = [&](const FieldMm& p, int i = -1) {
    return insideAnyRobot(p, i >= 0 ? blobs[i].at_team : nullptr);
  };
  // Whether another strong blob lies within a pattern's reach of blob i.
  auto dotsAround = [&](int i) {
    const double reach = RobotPatternGeometry::kSideBlobDistance + RobotPatternGeometry::kSideBlobRadius;
    for (int j = 0; j < n_strong; ++j)
      if (j != i && blobs[j].valid && dist(raw_positions[j], raw_positions[i]) < reach) return true;
    return false;
  };
  // Whether at least half the ring around blob i, where a robot's top
  // would show between its center dot and its side dots, is the carpet
  // (carpetAroundBall: by `colors`, or by darkness alone where null).
  auto carpetAround = [&](int i, const FrameColors* colors) {
    ImagePx px;
    double r;
    return ballInImage(i, px, r) && carpetAroundBall(frame_view, colors, px, r, opt.ball_radius,
                                                     blobs[i].brightness()) >= kMinCarpetAroundBall;
  };
  // The hue rule's cause, a thin line's demosaiced edge, lies on a marking,
  // and a robot's washed-out center dot has its side dots and its dark top
  // around it. A blob of a color no class explains with neither is a ball
  // whatever its hue: under a cold cast (0.72, 1, 1.62) at saturation 0.55
  // in H.264 at 5 Mbit/s the kicked ball came out pale yellow-gray, (83,
  // 87, 64) by the carpet's (44, 76, 58), in ten of the first twelve
  // frames. The ring is judged by darkness alone: there the carpet lay
  // nearer to the pale yellow centers than to the field class.
  auto aloneOnTheCarpet = [&](int i) {
    return !onMarking(blobs[i].at_ball) && !dotsAround(i) && carpetAround(i, nullptr);
  };
  // A blob nearest to a marker's class may be a ball in that marker's
  // color (a ball clipped in a sun patch): addMarkerColoredBalls judges it.
  // Nearest to another class but the carpet, off the markings, it may be a
  // ball clipped along its own path: a sun patch of 2.29 under a warm cast
  // at saturation 0.41 clipped one to (239, 237, 180), nearest to the
  // lines' white (moderate #1006); one of 1.97 at saturation 0.76 to (250,
  // 244, 149), nearest to yellow-green dots (#1020). On a marking that is
  // the lines' own color (a crossing of the center circle read (188, 192,
  // 135) there); beside a pattern's dot, a lost robot's washed-out center.
  auto keepIfMarkerColored = [&](int i, int nearest) {
    if (nearest == kYellow || nearest == kPink)
      marker_colored.push_back({i, nearest, {}, false});
    else if (nearest != kField && !onMarking(blobs[i].at_ball) && !dotsAround(i))
      marker_colored.push_back({i, -1, {}, false});
  };
  ColorVec field_sum;
  int field_n = 0;
  marker_colored.clear();
  for (int i = 0; i < n_strong; ++i) {  // never a weak peak
    const FrameBlob& b = blobs[i];
    if (!b.valid || b.robot >= 0) continue;
    const FieldMm p = b.at_ball;
    if (!inBallArea(p)) continue;
    ClippedColor seen(b.rgb);
    if (seen.saturated()) {
      // Over-exposed (a sun patch): two clipped channels say too little, so
      // the blob's color is read where its disc did not clip, a ball's
      // shaded rim. That is a mix with what lies around it, so it must also
      // stand alone: no other blob where a pattern's dots would be (a
      // clipped center dot of a robot not found has them), or, where one
      // is, the carpet where that robot's top would show. (Under a green
      // cast (0.8, 1.3, 0.8) a peak of the lit carpet 70 mm from the ball,
      // nearest to the green dots, hid it.)
      if (!b.has_unclipped || (dotsAround(i) && !carpetAround(i, &ball_colors))) continue;
      seen = ClippedColor(b.unclipped_rgb);
    }
    int nearest_neg = kField;
    bool unexpected = false;
    // On a marking, in a color near the lines' mix with the carpet, or
    // where markings meet (more line than one line's mix): a faded ball's
    // streak would look like the lines' own (BallColorJudge). A crossing
    // under tungsten in H.264 at 8 Mbit/s, 34 from one line's mix, read as
    // a faded ball.
    const bool line_colored =
        atCrossing(p) ||
        (onMarking(p) &&
         streakColorDistance(seen, ball_colors.color[kField], ball_colors.color[kWhite]) < kThinLineColorReach);
    const BallColorJudge& color_judge = line_colored ? judge_unfaded : judge;
    double color_conf = color_judge.confidence(seen, b.streak, &nearest_neg, &unexpected);
    // On a fast ball track's course the course is the evidence: a
    // compressed stream keeps color at half resolution and coarsest where
    // the picture moves, so a fast ball's streak may come out nearer to
    // pink or yellow than to orange. Whatever is not carpet there continues
    // the track, as sure as it lies near the prediction; so does a color no
    // class explains, whose hue the ball-color rules would judge (a fast
    // ball washed out to gray under a cold cast in H.264).
    BallCandidate c;
    c.blob = i;
    c.pos = p;
    const double temporal = ballTemporal(c, tracking);  // matches c to a track
    const double course = judge.isCarpet(seen.rgb()) ? 0.0 : courseConfidence(c);
    if (course > 0 && (unexpected || course > color_conf)) color_conf = course, unexpected = false;
    if (color_conf <= 0) {
      if (nearest_neg == kField && !b.streak) {
        for (int k = 0; k < 3; ++k) field_sum.c[k] += b.color.c[k];
        ++field_n;
      } else if (!b.streak && !insideRobot(p, i)) {
        keepIfMarkerColored(i, nearest_neg);
      }
      // A blob no color rule takes: its motion may still tell it
      // (fast_streaks.h).
      if (tracking && !judge.isCarpet(seen.rgb()) && !insideRobot(p, i) && !onMarking(p) && !onGoalWall(p)) {
        fast_streaks.add(p);
        const double chain = fast_streaks.confidence(p);
        if (chain >= opt.min_ball_confidence) {
          c.streak = b.streak;
          c.confidence = c.rank = chain;
          ball_cands.push_back(c);
        }
      }
      continue;
    }
    if (insideRobot(p, i)) continue;
    // A peak in the carpet's own chromaticity, within a color's noise of
    // the carpet beside the lines, is the carpet's, whatever the classes
    // say: at exposure 1.4 under tungsten a shaded streak peak at a robot's
    // edge read (67, 89, 55), 49 from a field class still at its reference
    // in a frame alone and nearer to a ball's mix with it (a false ball).
    if (carpet.valid && seen.distance(carpet_color) <= kMinClassRadius) continue;
    // A round blob of a shade no class explains is a ball only where its
    // color stays within one ball's rim (line crossings run on along their
    // lines). A fast ball's does not: motion stretches it, and the pixel
    // stage hides the streak candidate behind the round blob (nearBlob,
    // streak_score.h). So such a blob is judged as the streak it may be,
    // by the ball's mix with the carpet and the streak rules below (H.265 at
    // 5 Mbit/s lost the first frame's ball, kicked at 6 m/s, its chroma
    // washed out to (182, 110, 52), nearer to yellow than to orange).
    bool streak = b.streak;
    double color_conf_used = color_conf;
    // Nearer to orange than to any class, if only just (over-exposed under
    // a warm cast at gamma 0.65 a ball read (236, 177, 125), confidence
    // 0.15 against the lemon centers): where its hue lies clearly between
    // pink's and yellow's and it stands alone on the carpet, as a color no
    // class explains must, the place vouches for it in full.
    if (!unexpected && !b.streak && judge.hueClearlyBetweenPinkAndYellow(seen) && aloneOnTheCarpet(i))
      color_conf_used = 1;
    if (unexpected && !b.streak) {
      if (!judge.hueClearlyBetweenPinkAndYellow(seen) && !aloneOnTheCarpet(i)) {
        // In a marker's hue it may be a ball in that marker's color, as one
        // nearer to that class: a ball in a sun patch under tungsten, its red
        // clipped, reads as the yellow centers do.
        keepIfMarkerColored(i, nearest_neg);
        continue;
      }
      if (colorReachesBeyondRim(i, judge)) {
        const double as_streak = color_judge.confidence(seen, true);
        if (as_streak <= 0) continue;
        streak = true;
        color_conf_used = as_streak;
      }
    }
    // A streak's score is a shape measure of its own scale (streak_score.h).
    const double strength =
        b.streak ? std::min(1.0, b.score / kStreakFullStrength) : blobStrength(b.score, strength_ref);
    c.streak = streak;
    // An untracked streak on a goal's wall, or on a field marking in a color
    // near the lines' mix with the carpet, is no ball: a thin line's
    // demosaiced false colors (lines of 1 to 2 px at 1224 x 1024) make
    // short chroma runs along it, and under tungsten a white line or wall
    // mixed with the carpet looks like the ball mixed with it (a whole
    // center circle of false balls wherever no round ball hid them, 13..16
    // from the lines' mix; the goal posts' shaded faces 23..29; a fast ball
    // kicked along the center line, 70). Only a track it moved along
    // confirms it there: a streak is a ball in motion, and one that stays
    // put is the marking's own (the goal line's middle in H.265 at 3 Mbit/s
    // under tungsten, a track of itself for 14 frames). Not where the view
    // is stretched: seen at a grazing angle a ball at rest is a streak
    // itself (view_stretch.h). Nor, where markings cross, a round blob in
    // a color no class explains: the crossing's false colors stay within a
    // ball's rim as often as not (a warm cast at gamma 1.6: (104, 67, 54)
    // where the center circle meets the halfway line). Nor, on a marking,
    // where the blob shows a whole ball's round silhouette in the ball's
    // colors: a ball at rest, which the streak pass finds as it finds any
    // ball (at the field's corner the lines kept the round score from
    // peaking: extreme #32, a streak blob of (245, 97, 48)); a line's or a
    // corner's false color is no disc. A goal's post, seen from above, may
    // be one (extreme #676: the post's top read as a ball's silhouette).
    const bool moved_along_track = c.track >= 0 && !c.kicked && ball_tracker.tracks()[c.track].history >= 2 &&
                                   dist(p, ball_tracker.tracks()[c.track].pos[1]) > 2 * opt.ball_radius;
    if ((streak || (unexpected && atCrossing(p))) && !moved_along_track && (onGoalWall(p) || line_colored) &&
        !seenStretched(p) && (onGoalWall(p) || !wholeBallSilhouette(i, color_judge)))
      continue;
    c.confidence = color_conf_used * strength * temporal;
    // Beyond full strength the stronger blob ranks first among equals.
    c.rank = streak ? c.confidence : color_conf_used * blobStrengthRatio(b.score, strength_ref) * temporal;
    if (c.confidence >= opt.min_ball_confidence) {
      ball_cands.push_back(c);
    } else if (!streak) {
      // Too little orange, nearest to a marker: a ball clipped red in a sun
      // patch under tungsten is as near to the yellow centers as to orange.
      keepIfMarkerColored(i, nearest_neg);
    }
  }
  // Weak peaks on a fast ball's course, kept by the pixel pipeline where
  // expectedBalls said: a compressed stream can wash a fast ball out to one
  // (H.264 at 3 Mbit/s under a cold cast: a gray smear in every other
  // frame, scoring 0.06..0.24). Only an established course vouches for such
  // a peak, where no blob continued the track, and, as for a blob on the
  // course, only where the carpet does not explain its color (the smears
  // read (73, 93, 74) by the carpet's (42, 90, 74): no streak's color, the
  // ball's chroma gone). Nor does the peak move the track (course_only):
  // carpet texture near the prediction would bend it (H.265 at 3 Mbit/s: a
  // peak 45 mm off turned the ball's track aside, and its ghost took
  // another peak for a second ball). A ball keeps its line: such a peak
  // lies on it, off it by no more than a ball's blurred picture (as an
  // echo), and not behind the prediction by more than half a frame's
  // travel: there it is nearer to where the ball was a frame before, the
  // stream's stale copy of it (at 2448 x 2048, H.264 at 3 Mbit/s, one 118
  // mm behind, four frames into a coast).
  auto courseFree = [&](const BallCandidate& c) {
    if (c.track < 0) return false;
    const BallTrack& bt = ball_tracker.tracks()[c.track];
    double along = 0, across = 0;
    ball_tracker.onCourse(bt, bt.predicted, c.pos, along, across);
    const double step = BallTracker::speed(bt) * frame_interval;
    if (bt.hits < BallTracker::kEstablishedHits || across > 2 * opt.ball_radius || along < -0.5 * step) return false;
    for (const BallCandidate& o : ball_cands)
      if (o.track == c.track && !o.kicked) return false;
    return true;
  };
  // Where the frame shows it, a peak whose color differs from what lies
  // around it by no more than a color's noise (kMinClassRadius) is the
  // carpet's texture, whatever the classes say: in that stream the field
  // class never left its reference, 43 from the carpet's color. (There the
  // smears the course took differed from their ring by 15..51, the texture
  // peaks 65..118 mm from the ball by 2..13.)
  auto likeWhatLiesAround = [&](int i) {
    ImagePx px;
    double r;
    ColorVec around;
    return ballInImage(i, px, r) && colorAroundBall(frame_view, px, r, opt.ball_radius, around) &&
           ClippedColor(blobs[i].rgb).distance(around) <= kMinClassRadius;
  };
  bool fast_course = false;
  for (const BallTrack& bt : ball_tracker.tracks()) fast_course = fast_course || ball_tracker.isFast(bt);
  for (int i = n_strong; tracking && fast_course && i < static_cast<int>(blobs.size()); ++i) {
    const FrameBlob& b = blobs[i];
    if (!b.valid || b.robot >= 0 || judge.isCarpet(b.rgb)) continue;
    BallCandidate c;
    c.blob = i;
    c.pos = b.at_ball;
    ballTemporal(c, tracking);
    const double course = courseConfidence(c);
    if (course < opt.min_ball_confidence || !courseFree(c) || insideRobot(c.pos, i) || likeWhatLiesAround(i)) continue;
    c.confidence = c.rank = course;
    c.course_only = true;
    ball_cands.push_back(c);
  }
  // Balls cut by the image border, which make no blob (border_balls.h).
  // Such a ball's own blob, where part of it peaked, lies inward of its
  // center: the fit of the visible arc stands for it.
  border_balls.clear();
  if (frame_view.image && border_finder) border_finder->find(frame_view, judge, border_balls);
  for (size_t k = 0; k < border_balls.size(); ++k) {
    const BorderBall& bb = border_balls[k];
    BallCandidate c;
    c.border = static_cast<int>(k);
    c.pos = {bb.position.x, bb.position.y};
    const double color_conf = judge.confidence(bb.rgb, false);
    if (color_conf <= 0 || insideRobot(c.pos)) continue;
    // A whole ball the blob path found too is the blob's.
    auto blobNear = [&] {
      for (const BallCandidate& o : ball_cands)
        if (o.border < 0 && !o.streak && dist(o.pos, c.pos) < kSameBallRadii * opt.ball_radius) return true;
      return false;
    };
    if (bb.whole && blobNear()) continue;
    c.confidence = color_conf * std::min(1.0, bb.overlap / kBorderFullOverlap) * ballTemporal(c, tracking);
    c.rank = c.confidence;
    if (c.confidence < opt.min_ball_confidence) continue;
    ball_cands.erase(std::remove_if(ball_cands.begin(), ball_cands.end(),
                                    [&](const BallCandidate& o) {
                                      return o.border < 0 && !o.streak &&
                                             dist(o.pos, c.pos) < kSameBallRadii * opt.ball_radius;
                                    }),
                     ball_cands.end());
    ball_cands.push_back(c);
  }
  const bool marker_colored_ball = ball_cands.empty();
  if (marker_colored_ball) addMarkerColoredBalls(judge, strength_ref, tracking);
  if (ball_cands.empty()) addPaleBalls(strength_ref, tracking);
  selectBalls(ball_cands, opt.ball_radius, opt.max_balls);

  // Learn orange from a convincing ball, the field from the clutter.
  const float fp = static_cast<float>(opt.retention_force);
  const float fr = static_cast<float>(opt.reference_force);
  // (A streak's color is diluted by the carpet it passed over; a border
  // ball's is its visible part's, judged by pixels.)
  // (A ball in a marker's color is no sample of orange.)
  // (Nor is an over-exposed one's.)
  // (Nor is a weak peak the course vouched for.)
  if (!ball_cands.empty() && ball_cands[0].confidence >= 0.5 && ball_cands[0].blob >= 0 &&
      ball_cands[0].blob < n_strong &&
      !ball_cands[0].streak && !marker_colored_ball && !ClippedColor(blobs[ball_cands[0].blob].rgb).saturated())
    classes[kOrange].update(blobs[ball_cands[0].blob].color, fp, fr);
  if (field_n > 0) {
    for (int c = 0; c < 3; ++c) field_sum.c[c] /= field_n;
    classes[kField].update(field_sum, fp, fr);
  }

  if (tracking) ball_tracker.update(t, ball_cands);

  const double plane = plane_height;
  for (const auto& c : ball_cands) {
    BallDetection d;
    d.confidence = static_cast<float>(std::clamp(c.confidence, 0.0, 1.0));
    const BorderBall* bb = c.border >= 0 ? &border_balls[c.border] : nullptr;
    if (bb && !bb->whole) {
      d.position = bb->position;
      d.pixel = bb->center;
      out.balls.push_back(d);
      continue;
    }
    std::optional<ImagePx> px;
    if (bb) {
      px = bb->center;
    } else if (c.blob >= 0 && c.blob < n_strong) {
      const FieldMm at_plane = raw_positions[c.blob];
      px = camera.fieldToImage({at_plane.x, at_plane.y, plane});
    } else {
      px = camera.fieldToImage({c.pos.x, c.pos.y, opt.ball_radius});
    }
    // The ball's center from its silhouette (ball_silhouette.h). A far
    // ball seen from the side often peaks only as a streak; a real streak's
    // blur is no whole ball's silhouette and keeps its middle.
    if (px && frame_view.image) {
      const double r = ballRadiusPx(camera, {c.pos.x, c.pos.y, opt.ball_radius}, opt.ball_radius);
      std::optional<MarkerColoredBallTest> marker_test;
      if (marker_colored_ball)
        for (const auto& m : marker_colored)
          if (m.blob == c.blob) marker_test.emplace(ball_colors, judge, m.cls, m.has_around ? &m.around : nullptr);
      const BallColorTest& test = marker_test ? static_cast<const BallColorTest&>(*marker_test) : judge;
      ImagePx refined;
      if (ballSilhouetteCenter(frame_view, test, *px, r, refined)) px = refined;
    }
    std::optional<FieldPoint> fp3;
    if (px) fp3 = camera.imageToField(*px, opt.ball_radius);
    d.position = fp3 ? FieldPoint{fp3->x, fp3->y, opt.ball_radius}
                     : FieldPoint{c.pos.x, c.pos.y, opt.ball_radius};
    if (px) d.pixel = *px;
    out.balls.push_back(d);
  }
}

FieldMm Detector::Impl::seenAtHeight(const FieldMm& p, double z) const {
  const Eigen::Vector3d& c = camera.position();
  if (!(c.z() > opt.ball_radius)) return p;
  const double t = (c.z() - z) / (c.z() - opt.ball_radius);
  return {c.x() + (p.x - c.x()) * t, c.y() + (p.y - c.y()) * t};
}

// A marking is painted on the ground: the blob at p may be a ball near it
// or the line itself, seen where the camera's ray through p meets z = 0
// (farther out by the ball's height as the view tilts). At a corner of the
// field under tungsten a line's own streak lay 28 mm from the touch line on
// the ball's plane, 15 on the ground.
bool Detector::Impl::onMarking(const FieldMm& p) const {
  const double reach = opt.ball_radius + field.line_thickness / 2.0;
  return std::min(field.distanceToMarkings(p), field.distanceToMarkings(seenAtHeight(p, 0))) < reach;
}

bool Detector::Impl::atCrossing(const FieldMm& p) const {
  const double reach = opt.ball_radius + field.line_thickness / 2.0;
  return std::max(field.markingsWithin(p, reach), field.markingsWithin(seenAtHeight(p, 0), reach)) >= 2;
}

// A goal's wall stands goal_height tall: the ray through p may pass it at
// any height up to that (the top of a back corner 160 mm up lay 70 mm
// beyond the wall on the ball's plane, seen from the top-down camera).
bool Detector::Impl::onGoalWall(const FieldMm& p) const {
  const double reach = opt.ball_radius + FieldModel::kGoalWallThickness / 2;
  const FieldMm ground = seenAtHeight(p, 0), top = seenAtHeight(p, field.goal_height);
  const int n = static_cast<int>(std::ceil(dist(ground, top) / opt.ball_radius));
  for (int k = 0; k <= n; ++k) {
    const double s = n > 0 ? double(k) / n : 0.0;
    if (field.distanceToGoalWalls({ground.x + (top.x - ground.x) * s, ground.y + (top.y - ground.y) * s}) < reach)
      return true;
  }
  return false;
}

bool Detector::Impl::insideAnyRobot(const FieldMm& p, const FieldMm* at_team) const {
  const double keep_out = minBallOutsideDistance(opt.ball_radius);
  for (const auto& r : robots) {
    if (at_team && distanceToRobotTop(at_team[r.team == Team::Yellow ? 0 : 1], r.pose.position,
                                      r.pose.orientation) == 0)
      return true;
    if (dist(p, r.pose.position) > RobotPatternGeometry::kTopRadius + keep_out) continue;
    if (distanceToRobotTop(p, r.pose.position, r.pose.orientation) < keep_out) return true;
  }
  return false;
}

bool Detector::Impl::seenStretched(const FieldMm& p) const {
  double dir[2];
  return viewStretch(camera, p, opt.ball_radius, dir) >= kMinStretch;
}

bool Detector::Impl::ballInImage(int i, ImagePx& px, double& radius_px) const {
  if (!frame_view.image) return false;
  const FieldMm at_plane = raw_positions[i];
  const auto seen = camera.fieldToImage({at_plane.x, at_plane.y, plane_height});
  if (!seen) return false;
  px = *seen;
  const FieldMm& p = blobs[i].at_ball;
  radius_px = ballRadiusPx(camera, {p.x, p.y, opt.ball_radius}, opt.ball_radius);
  return true;
}

bool Detector::Impl::wholeBallSilhouette(int i, const BallColorTest& judge) const {
  ImagePx px, center;
  double r;
  return ballInImage(i, px, r) && ballSilhouetteCenter(frame_view, judge, px, r, center);
}

bool Detector::Impl::colorReachesBeyondRim(int i, const BallColorTest& judge) const {
  ImagePx px;
  double r;
  return ballInImage(i, px, r) && ballColorBeyondRim(frame_view, judge, px, r);
}

void Detector::Impl::addMarkerColoredBalls(const BallColorTest& judge, double strength_ref, bool tracking) {
  // One ball at most: this is the fallback where no ball of the ball's own
  // colors was found, and a sun patch's lit carpet makes many peaks alike
  // (extreme #589: six, the ball the strongest).
  int best = -1;
  for (auto& m : marker_colored) {
    const FrameBlob& b = blobs[m.blob];
    ImagePx px;
    double r;
    // Within the class's reach (a line's false colors, a mix with the
    // carpet, are not), round and alone (no color of it beyond its rim),
    // and most of what lies around it carpet, not a robot's top.
    // Its color, or a mix with the carpet the ring around it shows (isRim):
    // an over-exposed blob's by its unclipped rim, as findBalls judged it,
    // any other's by its mean, which blur with the carpet may keep below
    // the clip level though the ball clipped (extreme #690: (236, 177, 99)).
    if (!ballInImage(m.blob, px, r)) continue;
    m.has_around = colorAroundBall(frame_view, px, r, opt.ball_radius, m.around);
    const MarkerColoredBallTest test(ball_colors, judge, m.cls, m.has_around ? &m.around : nullptr);
    const float* rgb = !ClippedColor(b.rgb).saturated() ? b.rgb : b.has_unclipped ? b.unclipped_rgb : nullptr;
    // A peak no farther from its ring's color than a color's noise is that
    // carpet's texture (a sun patch's lit carpet, (197, 255, 130) in a ring
    // of its own color: a mix of the carpet with yellow as the frame's
    // classes saw it).
    if (rgb && m.has_around && ClippedColor(rgb).distance(m.around) <= kMinClassRadius) continue;
    const bool colored = rgb && (test.isBall(rgb) || test.isRim(rgb));
    // On a marking, a thin line's demosaiced false color can lie in a
    // marker's reach with the carpet beside it: there the blob must show a
    // whole ball's round silhouette (which has no color beyond its rim
    // either). A clipped blob's own color says too little for one; it was
    // judged by its rim.
    const bool round_needed = !ClippedColor(b.rgb).saturated() && onMarking(b.at_ball);
    ImagePx whole;
    if (!colored || (round_needed ? !ballSilhouetteCenter(frame_view, test, px, r, whole)
                                  : ballColorBeyondRim(frame_view, test, px, r)))
      continue;
    // Nearest to no marker, its color vouches least: no part of the ring
    // may be a robot's top. (A robot not found kept a yellow-green dot,
    // clipped pale in a sun patch, whose ring was half its top.)
    int may_be_top = 0;
    const double carpet =
        carpetAroundBall(frame_view, &ring_colors, px, r, opt.ball_radius, b.brightness(), &may_be_top);
    if (carpet < kMinCarpetAroundBall || (m.cls < 0 && may_be_top > 0)) continue;
    BallCandidate c;
    c.blob = m.blob;
    c.pos = b.at_ball;
    keepSurest(c, carpet, b.score, strength_ref, tracking, best);
  }
}

void Detector::Impl::keepSurest(BallCandidate c, double carpet, double score, double strength_ref, bool tracking,
                                int& best) {
  const double temporal = ballTemporal(c, tracking);
  c.confidence = carpet * blobStrength(score, strength_ref) * temporal;
  c.rank = carpet * blobStrengthRatio(score, strength_ref) * temporal;
  if (c.confidence < opt.min_ball_confidence || (best >= 0 && c.rank <= ball_cands[best].rank)) return;
  if (best < 0) best = static_cast<int>(ball_cands.size()), ball_cands.push_back(c);
  ball_cands[best] = c;
}

}  // namespace dv


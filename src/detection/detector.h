#pragma once
// Blob assignment (thesis §5.3): one camera frame's blobs -> robots (team, id,
// position, orientation) and balls, with confidence and optional tracking.
//
// Per frame:
//  1. every blob is moved along its camera ray from the blob plane to the
//     robot heights and the ball height (pattern offsets are mm on the robot
//     top, so the fit needs positions at that height);
//  2. position based hypotheses: each blob as a center, side blobs within
//     90 mm taken in increasing angle, scored with eq. 5.21, best per center,
//     no two robots overlapping by the rule shape;
//  3. position based color classes: k-means (k = 2) for yellow/blue centers
//     and green/pink sides with the separation test eq. 5.24, per-robot local
//     side colors, retention/reference forces eq. 5.25; a side slot without
//     a blob takes the marker color the frame shows there (seen_color.h);
//  4. tracking (§5.3.6): robots missing blobs are recovered from the
//     predicted pose with two or more blobs; identities change only after
//     several frames of agreeing contrary evidence; a frame that shares under
//     half its robots with the tracks starts afresh (an unrelated scene);
//  5. balls: blobs outside robots whose color is nearest to the learned
//     orange class among all learned classes, ranked by color margin, blob
//     strength and temporal consistency (a ball track predicts straight on,
//     mirrored at the walls; next to a robot it also takes a kicked ball
//     anywhere within max_ball_speed reach). Streak blobs (a ball too fast
//     for the round blob score, pipeline/streak_score.h) are only ever ball
//     candidates, their color compared with each class mixed with the field
//     color (the carpet the ball crossed during the exposure); beside a
//     round ball, a streak must continue a ball track.
#include <array>
#include <memory>
#include <vector>

#include "core/units.h"
#include "detection/seen_color.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "geometry/robot_pattern.h"
#include "pipeline/blob.h"

#include "detection/color_classes.h"

namespace dv {

struct RobotDetection {
  Team team = Team::Yellow;
  int id = 0;              // pattern id 0..15
  FieldMm position;        // robot center at its height
  double orientation = 0;  // rad, front direction, (-pi, pi]
  double height = 140;     // mm, the team's configured robot height
  float confidence = 0;    // 0..1
  ImagePx pixel;           // image pixel of the robot center
};

struct BallDetection {
  FieldPoint position;  // z = ball radius
  float confidence = 0;
  ImagePx pixel;
};

// Each list sorted by confidence, highest first.
struct Detections {
  std::vector<BallDetection> balls;
  std::vector<RobotDetection> robots;
};

// An RGB reference color (0..255 per channel). References are only weak
// priors: class colors are learned from the frames.
struct ColorRef {
  float r = 0, g = 0, b = 0;
};

struct DetectorOptions {
  double robot_height_yellow = 140;  // mm
  double robot_height_blue = 140;    // mm
  double ball_radius = 21.5;         // mm, balls are reported at z = radius
  bool tracking = true;

  // --- position based assignment (§5.3.3) ---
  double side_search_radius = 90;  // mm, side blobs around a center blob
  double score_scale = 10;         // mm, offset giving score 0.5 (eq. 5.21)
  double min_robot_score = 0.1;    // hypotheses below are dropped
  // Single-frame hypotheses need at least this many side blobs (the thesis
  // uses 4). With 3, a robot whose side blob the pixel stage missed is still
  // found (ranked at half its score); its id is then a guess (the missing
  // blob is taken as green) unless a track knows it.
  int min_side_blobs = 3;
  // Whether such a robot is reported when its id stays a guess (the frame
  // shows no clear color at the missing slot, no track saw it whole, and no
  // fully seen teammate rules one of the two ids out).
  // The protocol has no unknown id and a wrong one is a false robot: such
  // guesses were right 7 of 14 times over the scene sweep, 3 of 6 in the
  // side view, 33 of 42 in the 1224 x 1024 presets (7 of 7 under a blue
  // white balance, 24 of 33 in the dark and noisy frames), measured before
  // weak peaks filled most such missing blobs (weak_sides). Reported by
  // default, as teams expect every robot; `run --no-guessed-ids` puts
  // precision first. Its blobs are claimed either way, so they never become
  // balls.
  bool report_guessed_ids = true;

  // --- weak peaks as side blobs (weak_sides.h) ---
  // A pattern of a center blob and at least two side blobs may take weak
  // peaks (BlobList::weak) for its missing side blobs, each within this
  // distance of its predicted slot, when the whole pattern then fits with a
  // score (eq. 5.21) of at least min_weak_fit.
  bool weak_sides = true;
  double weak_side_tolerance = 10;  // mm
  double min_weak_fit = 0.5;        // all five blobs within 10 mm of the fit
  // A weak side's marker color (and one read from the frame, below) counts
  // only when its distance to the nearer side color is below this fraction
  // of its distance to the other.
  double weak_color_margin = 0.7;

  // --- side blobs that did not peak, read from the frame (seen_color.h) ---
  // A robot's side slot without a blob or a weak peak (its dot cut by the
  // image border, or one or two pixels tall far away) takes the marker
  // color the camera saw there, when a frame is given to process(): the
  // mean color of a disc of probe_radius mm around the slot, over the part
  // of it inside the image (at least min_probe_share of it), when clearly
  // nearer to the robot's own green or pink (weak_color_margin). On the
  // side view's robots (1.3..7.1 m away) the nearer color's distance is at
  // most 0.32 of the other's; in a sun patch (the sweep's
  // light_gradient_patches) a pale pink dot read 0.59.
  bool probe_missing_sides = true;
  double probe_radius = 13;        // mm, inside a 20 mm dot with room for pose error
  double min_probe_share = 0.05;

  // --- color classes (§5.3.5) ---
  double retention_force = 0.7;  // f_p, pull to the previous class color
  double reference_force = 0.1;  // f_r, pull to the reference color
  ColorRef ref_yellow{230, 210, 40};
  ColorRef ref_blue{40, 80, 200};
  ColorRef ref_green{60, 200, 80};
  ColorRef ref_pink{240, 90, 180};
  ColorRef ref_orange{255, 120, 20};
  ColorRef ref_field{40, 110, 50};
  ColorRef ref_white{235, 235, 235};

  // --- tracking (§5.3.6) ---
  double max_robot_acceleration = 6500;  // mm/s^2
  double max_prediction_dt = 0.05;       // s, cap in the uncertainty
  double min_uncertainty = 20;           // mm
  // A track seen in one frame only has no velocity yet: its uncertainty
  // covers this speed over the (capped) frame gap instead.
  double max_robot_speed = 4000;  // mm/s
  double track_gate = 90;                // mm, detection <-> track association
  // A tracked robot changes team/id only after this many consecutive frames
  // that agree on the same different identity.
  int identity_switch_frames = 3;

  // --- balls ---
  double min_ball_confidence = 0.3;
  double max_ball_speed = 6500;  // mm/s, gate for temporal consistency
  int max_balls = 8;
};

// Throws InputError("detector options", what) for impossible values
// (non-positive heights or radii, forces outside [0, 1] or summing above 1,
// a robot height at or above the camera, ...).
void validateDetectorOptions(const DetectorOptions& opt, const CameraModel& camera);

// What one frame says about the detector's color classes (for the warnings
// of color_health.h, the status and the console). Facts of this frame only.
struct DetectionHealth {
  int yellow = 0, blue = 0, balls = 0;  // reported
  int center_blobs = 0;  // robot centers the team clustering saw
  int side_blobs = 0;    // side blobs the green/pink clustering saw
  // Whether the clustering found two clusters (false with too few samples).
  bool teams_separated = false, sides_separated = false;
  float yellow_blue = 0, green_pink = 0;  // class distances (ColorSeparations)
  NeutralColor lines;  // the white lines' color: the camera's cast
};

class Detector {
 public:
  // Validates the options (see validateDetectorOptions).
  Detector(const CameraModel& camera, const FieldModel& field, const DetectorOptions& opt);
  ~Detector();
  Detector(Detector&&) noexcept;
  Detector& operator=(Detector&&) noexcept;

  // Forget all history (a new, unrelated frame or sequence).
  void reset();
  // New options (robot heights from the game controller, a reloaded config)
  // from the next frame on; tracks and learned colors are kept. Validates
  // first and throws InputError, keeping the old options, when invalid.
  void setOptions(const DetectorOptions& opt);
  // blobs: one frame's blobs on the plane blobs.plane_height; t_capture in
  // seconds. No allocation after warm-up (buffers are kept and reserved).
  // `frame`: the image the blobs came from, for the colors of side slots
  // that did not peak (probe_missing_sides); without it those stay unknown.
  void process(const BlobList& blobs, double t_capture, Detections& out,
               const FrameView& frame = {});

  // Where a fast ball (a track faster than any robot) will be in the next
  // frame, if it comes one frame interval after the last, on the last
  // frame's rectification plane; for the pixel pipeline, which then keeps
  // weak peaks there, as a compressed stream can wash such a ball out to
  // one (PixelPipeline::expect). None without tracking.
  void expectedBalls(ExpectedPlaces& out) const;

  const DetectorOptions& options() const { return opt_; }
  // The last processed frame's health record.
  const DetectionHealth& health() const;

  // Distances between the learned class colors (chromaticity, 0..300 scale
  // of color_classes.h) of the pairs the detector must tell apart; for the
  // health record (a pair that collapses is a class the camera lost).
  struct ColorSeparations {
    double yellow_blue = 0, green_pink = 0, orange_field = 0;
  };
  ColorSeparations colorSeparations() const;
  // The learned class colors (same scale), for the console's Colors page:
  // yellow, blue, green, pink, orange, field, white.
  static constexpr int kClassColorCount = 7;
  static const char* classColorName(int i);
  void classColors(ColorVec out[kClassColorCount]) const;

 private:
  struct Impl;
  DetectorOptions opt_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dv

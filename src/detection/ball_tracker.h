#pragma once
// Ball tracks across frames: a straight-on prediction mirrored at the
// walls, the gate around it (and around the last position next to a robot,
// where the ball may have been kicked), which candidate continues which
// track, and the echoes a compressed stream shows of a tracked ball. Knows
// nothing of blobs or colors: candidates come with position, rank and
// whether they are streaks.
#include <vector>

#include "core/units.h"
#include "geometry/field_model.h"

namespace dv {

struct BallTrack {
  FieldMm pos[2];  // [1] newest
  double t[2] = {0, 0};
  int history = 0;
  int hits = 0;
  bool confirmed = false;
  FieldMm predicted;
  double gate = 0;       // around the prediction
  double kick_gate = 0;  // around the last position, next to a robot
  double rank = 0;       // of the candidate that continued it this frame
  bool streak = false;   // that candidate was a streak (its rank is of another scale)
};

struct BallCandidate {
  int blob = -1;    // the detector's blob, or -1 with
  int border = -1;  // a ball cut by the image border
  FieldMm pos;      // at the ball's center height
  double confidence = 0;
  double rank = 0;  // orders equal confidences: the stronger evidence first
  bool streak = false;  // a fast-ball streak, not a round blob
  int track = -1;
  bool kicked = false;  // continues its track only as kicked (outside its course's gate)
  bool stale = false;  // where a kicked ball lay (BallTracker::update)
  // Only its track's course vouches for it (a weak peak): it is reported,
  // but neither moves nor starts a track, which goes on from its last blob.
  bool course_only = false;
};

struct BallTrackerOptions {
  FieldRect area;  // the field with its boundary: the walls
  double ball_radius = 21.5;       // mm
  double max_ball_speed = 6500;    // mm/s
  double max_robot_speed = 4000;   // mm/s
};

class BallTracker {
 public:
  // At most this many tracks (clutter must not grow them without bound).
  static constexpr size_t kMaxTracks = 16;

  explicit BallTracker(const BallTrackerOptions& o = {});
  void setOptions(const BallTrackerOptions& o) { opt_ = o; }
  void clear() { tracks_.clear(); }
  const std::vector<BallTrack>& tracks() const { return tracks_; }

  // Predicts every track at t: straight on from its last two positions,
  // mirrored at the walls it would cross. A ball within reach of one of
  // the n `robots` may also have been kicked anywhere it could get to.
  void predict(double t, const FieldMm* robots, int n);

  // The track candidate c continues: the nearest prediction within its
  // gate, else (as kicked, ranked behind) the nearest last position within
  // its kick gate. Sets c.track and c.kicked.
  void match(BallCandidate& c) const;

  // Commits frame t's balls (`cands`, in the order they were chosen; each
  // matched): a round blob where a kicked ball lay is dropped as its stale
  // picture, streaks on their tracks' courses continue them first, then
  // the others in order, one per track (none course_only); echoes of a
  // ball tracked in this frame are dropped; tracks unconfirmed for 0.1 s
  // end, and the balls that continued none start new ones (none
  // course_only).
  void update(double t, std::vector<BallCandidate>& cands);

  // mm/s over a track's last two positions (0 without two at distinct times).
  static double speed(const BallTrack& bt);
  // Whether a track moves faster than any robot (opt max_robot_speed) over
  // its last two positions: nothing but a ball moves so.
  bool isFast(const BallTrack& bt) const;
  // Where p lies from `from` along a track's last step and across it (mm).
  void onCourse(const BallTrack& bt, FieldMm from, FieldMm p, double& along, double& across) const;
  // Where the fast tracks will be at `t_next`, straight on and mirrored at
  // the walls (as predict); up to `max` into `out`, their count returned.
  int expectedFastBalls(double t_next, FieldMm* out, int max) const;

  // Whether c, continuing no track, lies on the course of a ball tracked
  // at t within the distance it covers in kEchoTime, ranked below it.
  bool isEcho(const BallCandidate& c, double t) const;

  // How far back and ahead of a tracked ball its echoes lie, in time at
  // its speed: the span of a stream's reference frames (at 60 fps a group
  // of B-frames spans 4 frames), as long as a ball track survives a gap.
  static constexpr double kEchoTime = 0.1;
  // A ball track continued this many frames has an established course.
  static constexpr int kEstablishedHits = 3;

 private:
  FieldMm reflectAtWalls(FieldMm from, FieldMm p) const;
  // A track with two positions at distinct times, dt after its last one.
  FieldMm straightOn(const BallTrack& bt, double dt) const;

  BallTrackerOptions opt_;
  std::vector<BallTrack> tracks_;
};

}  // namespace dv

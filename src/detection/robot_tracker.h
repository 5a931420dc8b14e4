#pragma once
// Robot tracks across frames (thesis §5.3.6): a constant-velocity
// prediction, association of the frame's robots to the predictions,
// recovery of the tracks nobody continued, and identity hysteresis (a
// tracked robot keeps team and id until several frames agree on another).
// Knows nothing of blobs or colors: recovery is the caller's (TrackHooks).
#include <cstdint>
#include <vector>

#include "detection/robot_hypothesis.h"

namespace dv {

struct DetectorOptions;

struct RobotTrackerOptions {
  double max_robot_acceleration = 6500;  // mm/s^2
  double max_prediction_dt = 0.05;       // s, cap in the uncertainty
  double min_uncertainty = 20;           // mm
  double max_robot_speed = 4000;         // mm/s, a track seen once
  double track_gate = 90;                // mm, robot <-> prediction
  int identity_switch_frames = 3;
  static RobotTrackerOptions from(const DetectorOptions& o);
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
  double uncertainty = 0;  // mm around `predicted`
};

// What the tracker asks of the detector.
class TrackHooks {
 public:
  virtual ~TrackHooks() = default;
  // Looks for the robot of `track` (no robot of this frame continued it)
  // around its prediction; appends it to `robots` and returns true when found.
  virtual bool recover(const RobotTrack& track, int index, std::vector<Hypothesis>& robots) = 0;
  // The tracker changed the team of `h` (hysteresis): fit it again at that team's height.
  virtual void refit(Hypothesis& h) = 0;
};

class RobotTracker {
 public:
  // Robots a frame and the tracks must both have before their overlap can
  // say whether the frame continues the tracked scene.
  static constexpr int kSceneCheckMinRobots = 4;

  explicit RobotTracker(const RobotTrackerOptions& o = {});
  void setOptions(const RobotTrackerOptions& o) { opt_ = o; }
  void clear() { tracks_.clear(); }
  const std::vector<RobotTrack>& tracks() const { return tracks_; }

  // One frame taken at t: `robots` are its robots in rank order. Each that
  // continues a track takes the track's identity (hysteresis) and id_known
  // where the track once saw it whole; tracks nobody continued are offered
  // to hooks.recover; tracks still unconfirmed end, and the robots that
  // continued none start new ones. Returns true when the frame shows an
  // unrelated scene (it meets fewer than half of the tracks it could): the
  // old tracks are dropped first.
  bool update(double t, std::vector<Hypothesis>& robots, TrackHooks& hooks);

 private:
  void predict(double t);
  void associate(const std::vector<Hypothesis>& robots);
  bool unrelated(int fresh) const;
  void applyIdentity(RobotTrack& tr, Hypothesis& h, TrackHooks& hooks) const;
  static void advance(RobotTrack& tr, const Hypothesis& h, double t);

  RobotTrackerOptions opt_;
  std::vector<RobotTrack> tracks_;
  std::vector<int> match_;      // per robot: track index or -1
  std::vector<uint8_t> taken_;  // per track
};

}  // namespace dv

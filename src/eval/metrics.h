#pragma once
// Scoring detections against ground truth, frame by frame.
//
// Within one frame, truth and detections are paired greedily, closest pair
// first, each object used at most once, only within the match radius:
//  - a robot *match* needs the same team and the same id (recall, precision,
//    position and orientation errors are over these);
//  - a *team match* ignores the id (team-only recall; ID accuracy is the
//    share of team matches whose id is right);
//  - a ball match needs only the distance.
// A false positive is a detection that has no counterpart at all: a robot
// without a team match, a ball without a ball match. (A robot with the wrong
// id is an id error, not a false positive, but it lowers precision.)
// Distances are in the field plane (x, y), millimetres.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "dotvision/ssl_detection.pb.h"

namespace dv {

struct MatchOptions {
  double robot_radius_mm = 60;
  double ball_radius_mm = 50;
};

// Median and 95th percentile of a sample (0 for an empty one).
struct ErrorStats {
  double median = 0;
  double p95 = 0;
  long count = 0;
};
ErrorStats errorStats(std::vector<double> values);

// Nearest-rank percentile, q in [0, 1]; 0 for an empty sample.
double percentile(std::vector<double> values, double q);

// Where something went wrong, for the field map of `eval --plot`.
struct Miss {
  enum Kind { RobotMissed, RobotWrongId, FalseRobot, BallMissed, FalseBall };
  Kind kind = RobotMissed;
  double x = 0, y = 0;  // field mm: the truth's place, or the false detection's
};

struct Metrics {
  long frames = 0;                   // truth frames scored
  long frames_missing = 0;           // truth frames with no detection frame
  long truth_robots = 0;
  long detected_robots = 0;
  long matched_robots = 0;           // same team, same id, within radius
  long team_matched_robots = 0;      // same team, within radius
  long team_matched_correct_id = 0;  // of those, with the right id
  long truth_balls = 0;
  long detected_balls = 0;
  long matched_balls = 0;
  long false_positive_robots = 0;
  long false_positive_balls = 0;
  std::vector<double> robot_position_errors_mm;
  std::vector<double> robot_orientation_errors_rad;
  std::vector<double> ball_position_errors_mm;
  std::vector<Miss> misses;

  // Ratios; 1 where the denominator is 0 would hide a problem, so they
  // return 0 then, except precision with no detections and no truth (1).
  double robotRecall() const;
  double robotPrecision() const;
  double teamRecall() const;
  double idAccuracy() const;
  double ballRecall() const;
  double ballPrecision() const;
  double falsePositivesPerFrame() const;

  void add(const Metrics& other);
};

// Scores one frame; `detections` may be null (camera produced nothing).
void scoreFrame(const ssl::SSL_DetectionFrame& truth, const ssl::SSL_DetectionFrame* detections,
                const MatchOptions& options, Metrics& out);

struct EvalReport {
  Metrics overall;
  std::map<uint32_t, Metrics> per_camera;
  long detection_frames = 0;           // read from the detection file
  long detection_frames_unmatched = 0; // no truth frame with that key
  long duplicate_detection_frames = 0; // same (camera, frame) twice: first kept
};

// Pairs frames by (camera_id, frame_number) and scores each truth frame.
EvalReport evaluate(const std::vector<ssl::SSL_DetectionFrame>& truth,
                    const std::vector<ssl::SSL_DetectionFrame>& detections,
                    const MatchOptions& options = {});

// Human-readable table: overall first, then each camera.
std::string formatReport(const EvalReport& report);
// The same as one JSON object (see docs for field names).
std::string reportJson(const EvalReport& report);

}  // namespace dv

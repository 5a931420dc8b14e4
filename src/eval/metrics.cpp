#include "eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <utility>

namespace dv {

namespace {

constexpr double kTwoPi = 2 * 3.14159265358979323846;

double ratio(long num, long den) { return den > 0 ? static_cast<double>(num) / den : 0.0; }

double angleDifference(double a, double b) {
  double d = std::fmod(a - b, kTwoPi);
  if (d > kTwoPi / 2) d -= kTwoPi;
  if (d < -kTwoPi / 2) d += kTwoPi;
  return std::abs(d);
}

struct Pair {
  int truth;
  int detection;
  double distance;
};

// Greedy one-to-one pairing, closest first, of the pairs `allowed` lets
// through and within `radius`. Returns for each truth index its detection
// index or -1.
template <typename Truth, typename Det, typename Allowed>
std::vector<int> pairClosest(const Truth& truth, const Det& det, double radius, Allowed allowed,
                             std::vector<int>* det_to_truth = nullptr) {
  std::vector<Pair> pairs;
  for (int i = 0; i < truth.size(); ++i) {
    for (int j = 0; j < det.size(); ++j) {
      if (!allowed(i, j)) continue;
      const double d = std::hypot(truth.Get(i).x() - det.Get(j).x(), truth.Get(i).y() - det.Get(j).y());
      if (d <= radius) pairs.push_back({i, j, d});
    }
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const Pair& a, const Pair& b) { return a.distance < b.distance; });
  std::vector<int> t2d(static_cast<size_t>(truth.size()), -1);
  std::vector<int> d2t(static_cast<size_t>(det.size()), -1);
  for (const Pair& p : pairs) {
    if (t2d[p.truth] >= 0 || d2t[p.detection] >= 0) continue;
    t2d[p.truth] = p.detection;
    d2t[p.detection] = p.truth;
  }
  if (det_to_truth) *det_to_truth = std::move(d2t);
  return t2d;
}

using Robots = google::protobuf::RepeatedPtrField<ssl::SSL_DetectionRobot>;

void scoreTeam(const Robots& truth, const Robots* det, const MatchOptions& o, Metrics& m) {
  static const Robots kNone;
  const Robots& d = det ? *det : kNone;
  m.truth_robots += truth.size();
  m.detected_robots += d.size();

  auto same_id = [&](int i, int j) {
    return truth.Get(i).has_robot_id() && d.Get(j).has_robot_id() &&
           truth.Get(i).robot_id() == d.Get(j).robot_id();
  };
  const std::vector<int> full = pairClosest(truth, d, o.robot_radius_mm, same_id);
  for (int i = 0; i < truth.size(); ++i) {
    const int j = full[i];
    if (j < 0) continue;
    ++m.matched_robots;
    const auto& t = truth.Get(i);
    const auto& r = d.Get(j);
    m.robot_position_errors_mm.push_back(std::hypot(t.x() - r.x(), t.y() - r.y()));
    if (t.has_orientation() && r.has_orientation())
      m.robot_orientation_errors_rad.push_back(angleDifference(t.orientation(), r.orientation()));
  }

  std::vector<int> det_to_truth;
  const std::vector<int> team = pairClosest(
      truth, d, o.robot_radius_mm, [](int, int) { return true; }, &det_to_truth);
  for (int i = 0; i < truth.size(); ++i) {
    const int j = team[i];
    if (j < 0) {
      m.misses.push_back({Miss::RobotMissed, truth.Get(i).x(), truth.Get(i).y()});
      continue;
    }
    ++m.team_matched_robots;
    if (same_id(i, j)) {
      ++m.team_matched_correct_id;
    } else {
      m.misses.push_back({Miss::RobotWrongId, truth.Get(i).x(), truth.Get(i).y()});
    }
  }
  for (size_t j = 0; j < det_to_truth.size(); ++j)
    if (det_to_truth[j] < 0) {
      ++m.false_positive_robots;
      m.misses.push_back({Miss::FalseRobot, d.Get(static_cast<int>(j)).x(), d.Get(static_cast<int>(j)).y()});
    }
}

}  // namespace

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  // Nearest rank: the smallest value with at least q of the sample at or below it.
  const double rank = std::ceil(q * static_cast<double>(values.size()));
  const size_t index = rank < 1 ? 0 : std::min(values.size() - 1, static_cast<size_t>(rank) - 1);
  return values[index];
}

ErrorStats errorStats(std::vector<double> values) {
  ErrorStats s;
  s.count = static_cast<long>(values.size());
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  s.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  s.p95 = percentile(std::move(values), 0.95);
  return s;
}

double Metrics::robotRecall() const { return ratio(matched_robots, truth_robots); }
double Metrics::robotPrecision() const {
  return detected_robots == 0 && truth_robots == 0 ? 1.0 : ratio(matched_robots, detected_robots);
}
double Metrics::teamRecall() const { return ratio(team_matched_robots, truth_robots); }
double Metrics::idAccuracy() const { return ratio(team_matched_correct_id, team_matched_robots); }
double Metrics::ballRecall() const { return ratio(matched_balls, truth_balls); }
double Metrics::ballPrecision() const {
  return detected_balls == 0 && truth_balls == 0 ? 1.0 : ratio(matched_balls, detected_balls);
}
double Metrics::falsePositivesPerFrame() const {
  return frames > 0 ? static_cast<double>(false_positive_robots + false_positive_balls) / frames : 0.0;
}

void Metrics::add(const Metrics& o) {
  frames += o.frames;
  frames_missing += o.frames_missing;
  truth_robots += o.truth_robots;
  detected_robots += o.detected_robots;
  matched_robots += o.matched_robots;
  team_matched_robots += o.team_matched_robots;
  team_matched_correct_id += o.team_matched_correct_id;
  truth_balls += o.truth_balls;
  detected_balls += o.detected_balls;
  matched_balls += o.matched_balls;
  false_positive_robots += o.false_positive_robots;
  false_positive_balls += o.false_positive_balls;
  auto append = [](std::vector<double>& a, const std::vector<double>& b) {
    a.insert(a.end(), b.begin(), b.end());
  };
  append(robot_position_errors_mm, o.robot_position_errors_mm);
  append(robot_orientation_errors_rad, o.robot_orientation_errors_rad);
  append(ball_position_errors_mm, o.ball_position_errors_mm);
  misses.insert(misses.end(), o.misses.begin(), o.misses.end());
}

void scoreFrame(const ssl::SSL_DetectionFrame& truth, const ssl::SSL_DetectionFrame* det,
                const MatchOptions& options, Metrics& m) {
  ++m.frames;
  if (!det) ++m.frames_missing;
  scoreTeam(truth.robots_yellow(), det ? &det->robots_yellow() : nullptr, options, m);
  scoreTeam(truth.robots_blue(), det ? &det->robots_blue() : nullptr, options, m);

  static const google::protobuf::RepeatedPtrField<ssl::SSL_DetectionBall> kNoBalls;
  const auto& balls = det ? det->balls() : kNoBalls;
  m.truth_balls += truth.balls_size();
  m.detected_balls += balls.size();
  std::vector<int> det_to_truth;
  const std::vector<int> t2d = pairClosest(
      truth.balls(), balls, options.ball_radius_mm, [](int, int) { return true; }, &det_to_truth);
  for (int i = 0; i < truth.balls_size(); ++i) {
    if (t2d[i] < 0) {
      m.misses.push_back({Miss::BallMissed, truth.balls(i).x(), truth.balls(i).y()});
      continue;
    }
    ++m.matched_balls;
    const auto& t = truth.balls(i);
    const auto& b = balls.Get(t2d[i]);
    m.ball_position_errors_mm.push_back(std::hypot(t.x() - b.x(), t.y() - b.y()));
  }
  for (size_t j = 0; j < det_to_truth.size(); ++j)
    if (det_to_truth[j] < 0) {
      ++m.false_positive_balls;
      m.misses.push_back({Miss::FalseBall, balls.Get(static_cast<int>(j)).x(), balls.Get(static_cast<int>(j)).y()});
    }
}

EvalReport evaluate(const std::vector<ssl::SSL_DetectionFrame>& truth,
                    const std::vector<ssl::SSL_DetectionFrame>& detections,
                    const MatchOptions& options) {
  EvalReport report;
  report.detection_frames = static_cast<long>(detections.size());
  std::map<std::pair<uint32_t, uint32_t>, const ssl::SSL_DetectionFrame*> by_key;
  for (const auto& d : detections) {
    if (!by_key.emplace(std::make_pair(d.camera_id(), d.frame_number()), &d).second)
      ++report.duplicate_detection_frames;
  }
  std::map<std::pair<uint32_t, uint32_t>, bool> truth_keys;
  for (const auto& t : truth) {
    const auto key = std::make_pair(t.camera_id(), t.frame_number());
    truth_keys[key] = true;
    const auto it = by_key.find(key);
    scoreFrame(t, it == by_key.end() ? nullptr : it->second, options, report.per_camera[t.camera_id()]);
  }
  for (const auto& [key, frame] : by_key)
    if (!truth_keys.count(key)) ++report.detection_frames_unmatched;
  for (const auto& [camera, m] : report.per_camera) report.overall.add(m);
  return report;
}

namespace {

nlohmann::json metricsJson(const Metrics& m) {
  const ErrorStats pos = errorStats(m.robot_position_errors_mm);
  const ErrorStats ori = errorStats(m.robot_orientation_errors_rad);
  const ErrorStats ball = errorStats(m.ball_position_errors_mm);
  return {
      {"frames", m.frames},
      {"frames_missing", m.frames_missing},
      {"robots",
       {{"truth", m.truth_robots},
        {"detected", m.detected_robots},
        {"matched", m.matched_robots},
        {"recall", m.robotRecall()},
        {"precision", m.robotPrecision()},
        {"team_matched", m.team_matched_robots},
        {"team_recall", m.teamRecall()},
        {"id_accuracy", m.idAccuracy()},
        {"false_positives", m.false_positive_robots},
        {"position_error_mm", {{"median", pos.median}, {"p95", pos.p95}, {"count", pos.count}}},
        {"orientation_error_rad", {{"median", ori.median}, {"p95", ori.p95}, {"count", ori.count}}}}},
      {"balls",
       {{"truth", m.truth_balls},
        {"detected", m.detected_balls},
        {"matched", m.matched_balls},
        {"recall", m.ballRecall()},
        {"precision", m.ballPrecision()},
        {"false_positives", m.false_positive_balls},
        {"position_error_mm", {{"median", ball.median}, {"p95", ball.p95}, {"count", ball.count}}}}},
      {"false_positives_per_frame", m.falsePositivesPerFrame()},
  };
}

void appendMetricsText(std::string& out, const std::string& title, const Metrics& m) {
  const ErrorStats pos = errorStats(m.robot_position_errors_mm);
  const ErrorStats ori = errorStats(m.robot_orientation_errors_rad);
  const ErrorStats ball = errorStats(m.ball_position_errors_mm);
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "%s: %ld frames (%ld without detections)\n"
                "  robots: recall %.3f  precision %.3f  team recall %.3f  id accuracy %.3f"
                "  (truth %ld, detected %ld, matched %ld)\n"
                "          position error median %.1f mm  p95 %.1f mm;"
                "  orientation error median %.3f rad  p95 %.3f rad\n"
                "  balls:  recall %.3f  precision %.3f  (truth %ld, detected %ld, matched %ld)"
                "  position error median %.1f mm  p95 %.1f mm\n"
                "  false positives per frame: %.3f (robots %ld, balls %ld)\n",
                title.c_str(), m.frames, m.frames_missing, m.robotRecall(), m.robotPrecision(),
                m.teamRecall(), m.idAccuracy(), m.truth_robots, m.detected_robots, m.matched_robots,
                pos.median, pos.p95, ori.median, ori.p95, m.ballRecall(), m.ballPrecision(),
                m.truth_balls, m.detected_balls, m.matched_balls, ball.median, ball.p95,
                m.falsePositivesPerFrame(), m.false_positive_robots, m.false_positive_balls);
  out += buf;
}

}  // namespace

std::string formatReport(const EvalReport& report) {
  std::string out;
  appendMetricsText(out, "overall", report.overall);
  for (const auto& [camera, m] : report.per_camera)
    appendMetricsText(out, "camera " + std::to_string(camera), m);
  if (report.detection_frames_unmatched > 0)
    out += "note: " + std::to_string(report.detection_frames_unmatched) +
           " detection frames have no truth frame with the same (camera_id, frame_number)\n";
  if (report.duplicate_detection_frames > 0)
    out += "note: " + std::to_string(report.duplicate_detection_frames) +
           " detection frames repeat a (camera_id, frame_number); the first was used\n";
  return out;
}

std::string reportJson(const EvalReport& report) {
  nlohmann::json j;
  j["overall"] = metricsJson(report.overall);
  nlohmann::json cams = nlohmann::json::object();
  for (const auto& [camera, m] : report.per_camera) cams[std::to_string(camera)] = metricsJson(m);
  j["per_camera"] = cams;
  j["detection_frames"] = report.detection_frames;
  j["detection_frames_unmatched"] = report.detection_frames_unmatched;
  j["duplicate_detection_frames"] = report.duplicate_detection_frames;
  return j.dump();
}

}  // namespace dv

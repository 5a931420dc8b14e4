#include "geometry/calibration/calibration_report.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "geometry/calibration/field_line_model.h"

namespace dv {

namespace {

// A group counts as explained when most of its pixels lie on its model line.
constexpr double kGatePx = 10, kUsedMeanPx = 2.0, kUsedShare = 0.6;

LineGroupResidual groupResidual(const LineGroup& g, const CameraModel& cam, const FieldLineModel& model) {
  LineGroupResidual r;
  r.extent_px = g.extent_px;
  r.pixels = int(g.pixels.size());
  std::map<int, int> votes;
  double sum_px = 0, sum_mm = 0;
  for (const auto& px : g.pixels) {
    const auto a = cam.imageToField(px, 0);
    const auto b = cam.imageToField({px.u + 1, px.v}, 0);
    const auto d = cam.imageToField({px.u, px.v + 1}, 0);
    if (!a || !b || !d) continue;
    const double scale = 0.5 * (std::hypot(b->x - a->x, b->y - a->y) + std::hypot(d->x - a->x, d->y - a->y));
    const auto near = model.nearest(a->xy());
    if (near.element < 0 || !(scale > 0) || near.distance / scale > kGatePx) continue;
    ++r.matched;
    ++votes[near.element];
    sum_px += near.distance / scale;
    sum_mm += near.distance;
  }
  if (r.matched > 0) {
    r.mean_px = sum_px / r.matched;
    r.mean_mm = sum_mm / r.matched;
    const auto top = std::max_element(votes.begin(), votes.end(),
                                      [](const auto& x, const auto& y) { return x.second < y.second; });
    r.line = model.elements()[top->first].name;
    if (r.line.empty()) r.line = "line " + std::to_string(top->first);
  }
  r.used = r.pixels > 0 && r.matched >= kUsedShare * r.pixels && r.mean_px <= kUsedMeanPx;
  return r;
}

nlohmann::json xyz(const FieldPoint& p) { return {p.x, p.y, p.z}; }
nlohmann::json xy(const FieldMm& p) { return {p.x, p.y}; }

}  // namespace

CalibrationReport makeCalibrationReport(const CalibrationOutcome& o, const FieldModel& field,
                                        const std::string& image, uint32_t camera_id, double seconds) {
  CalibrationReport r;
  r.image = image;
  r.camera_id = camera_id;
  r.mode = o.automatic ? "automatic" : "points";
  r.seconds = seconds;
  r.line_pixels = int(o.lines.pixels.size());
  if (o.intrinsics) r.distortion_groups = o.intrinsics->groups_used, r.distortion_rms_px = o.intrinsics->rms_px;
  r.has_calibration = o.has_pose;
  r.symmetry = o.symmetry;
  r.passed = !o.problem;
  r.verdict = o.problem ? *o.problem : "passed";
  if (r.has_calibration) {
    r.calibration = o.calibration;
    r.measures = o.measures;
    r.lens = o.lens;
    r.league_fit = leagueFit(o.calibration);
    const CameraModel cam(o.calibration);
    const FieldLineModel model(field);
    for (const auto& g : o.lines.groups) {
      r.groups.push_back(groupResidual(g, cam, model));
      r.groups_used += r.groups.back().used;
    }
    const Eigen::Vector3d axis = cam.rotation().transpose() * Eigen::Vector3d(0, 0, 1);
    r.tilt_deg = std::acos(std::clamp(-axis.z(), -1.0, 1.0)) * 180 / kPi;
    r.heading_deg = std::atan2(axis.y(), axis.x()) * 180 / kPi;
  } else {
    for (const auto& g : o.lines.groups) {
      LineGroupResidual gr;
      gr.extent_px = g.extent_px;
      gr.pixels = int(g.pixels.size());
      r.groups.push_back(gr);
    }
  }
  return r;
}

std::string formatReport(const CalibrationReport& r) {
  std::string s;
  char buf[400];
  std::snprintf(buf, sizeof buf, "calibration report: camera %u from %s (%s mode, %.2f s)\n", r.camera_id,
                r.image.c_str(), r.mode.c_str(), r.seconds);
  s += buf;
  std::snprintf(buf, sizeof buf,
                "  lines: %d line pixels, %zu line groups found, %d used; lens fitted on %d long groups "
                "(straightness %.2f px)\n",
                r.line_pixels, r.groups.size(), r.groups_used, r.distortion_groups, r.distortion_rms_px);
  s += buf;
  for (size_t i = 0; i < r.groups.size(); ++i) {
    const auto& g = r.groups[i];
    if (r.has_calibration && g.matched > 0)
      std::snprintf(buf, sizeof buf, "    group %2zu: %5.0f px long, %4d px, %-22s residual %.2f px (%.1f mm)%s\n",
                    i, g.extent_px, g.pixels, g.line.c_str(), g.mean_px, g.mean_mm, g.used ? "" : "  not used");
    else
      std::snprintf(buf, sizeof buf, "    group %2zu: %5.0f px long, %4d px, %s\n", i, g.extent_px, g.pixels,
                    r.has_calibration ? "matches no field line" : "no pose to compare with");
    s += buf;
  }
  if (r.has_calibration) {
    const auto& c = r.calibration;
    const CameraModel cam(c);
    std::snprintf(buf, sizeof buf,
                  "  parameters: focal length %.1f px, principal point (%.1f, %.1f) px, distortion %.4f, "
                  "camera at (%.0f, %.0f, %.0f) mm, tilt %.1f deg, heading %.1f deg\n",
                  c.focal_length, c.principal_point_x, c.principal_point_y, c.distortion, cam.position().x(),
                  cam.position().y(), cam.position().z(), r.tilt_deg, r.heading_deg);
    s += buf;
    const auto& m = r.measures;
    std::snprintf(buf, sizeof buf,
                  "  fit: line overlap %.3f, mean line distance %.3f px (%.2f mm), model lines seen %.0f%%\n",
                  m.overlap_ratio, m.mean_distance_px, m.mean_distance_mm, 100 * m.model_support);
    s += buf;
    if (r.lens) {
      const auto& l = c.lens;
      std::snprintf(buf, sizeof buf,
                    "  lens: %s; line residual (rms) league model %.3f px, with k2 k3 p1 p2 %.3f px over %d line bins, "
                    "information gain %.1f\n",
                    r.lens->lens_used ? "terms beyond the league's model taken" : "the league's model",
                    r.lens->league_rms_px, r.lens->lens_rms_px, r.lens->pixels, r.lens->information_gain);
      s += buf;
      if (l.any()) {
        std::snprintf(buf, sizeof buf, "    k2 %.6f, k3 %.6f, p1 %.6f, p2 %.6f\n", l.k2, l.k3, l.p1, l.p2);
        s += buf;
      }
    }
    if (r.league_fit && c.lens.any()) {
      const auto& p = r.league_fit->calibration;
      std::snprintf(buf, sizeof buf,
                    "  published (league model's best fit): focal length %.1f px, principal point (%.1f, %.1f) px, "
                    "distortion %.4f; field error against the lens %.2f mm mean, %.2f mm max\n",
                    p.focal_length, p.principal_point_x, p.principal_point_y, p.distortion,
                    r.league_fit->residual.mean_mm, r.league_fit->residual.max_mm);
      s += buf;
    }
  }
  if (r.symmetry) s += "  " + r.symmetry->describe() + "\n";
  s += r.passed ? "  verdict: passed\n" : "  verdict: REFUSED: " + r.verdict + "\n";
  return s;
}

nlohmann::json reportToJson(const CalibrationReport& r) {
  nlohmann::json groups = nlohmann::json::array();
  for (const auto& g : r.groups) {
    nlohmann::json j = {{"extent_px", g.extent_px}, {"pixels", g.pixels}, {"matched", g.matched},
                        {"used", g.used}};
    if (r.has_calibration && g.matched > 0)
      j["line"] = g.line, j["mean_residual_px"] = g.mean_px, j["mean_residual_mm"] = g.mean_mm;
    groups.push_back(j);
  }
  nlohmann::json j = {
      {"image", r.image},
      {"camera_id", r.camera_id},
      {"mode", r.mode},
      {"seconds", r.seconds},
      {"verdict", {{"passed", r.passed}, {"reason", r.passed ? "" : r.verdict}}},
      {"lines",
       {{"line_pixels", r.line_pixels},
        {"groups_found", r.groups.size()},
        {"groups_used", r.groups_used},
        {"distortion_groups", r.distortion_groups},
        {"distortion_rms_px", r.distortion_rms_px},
        {"groups", groups}}}};
  if (r.has_calibration) {
    const auto& c = r.calibration;
    const CameraModel cam(c);
    j["parameters"] = {{"focal_length_px", c.focal_length},
                       {"principal_point_px", {c.principal_point_x, c.principal_point_y}},
                       {"distortion", c.distortion},
                       {"position_mm", {cam.position().x(), cam.position().y(), cam.position().z()}},
                       {"tilt_deg", r.tilt_deg},
                       {"heading_deg", r.heading_deg}};
    if (r.lens)
      j["lens"] = {{"terms_used", r.lens->lens_used},
                   {"k2", c.lens.k2}, {"k3", c.lens.k3}, {"p1", c.lens.p1}, {"p2", c.lens.p2},
                   {"line_rms_px", {{"league", r.lens->league_rms_px}, {"lens", r.lens->lens_rms_px}}},
                   {"pixels", r.lens->pixels},
                   {"information_gain", r.lens->information_gain}};
    if (r.league_fit) {
      const auto& p = r.league_fit->calibration;
      j["published"] = {{"focal_length_px", p.focal_length},
                        {"principal_point_px", {p.principal_point_x, p.principal_point_y}},
                        {"distortion", p.distortion},
                        {"field_error_mm", {{"mean", r.league_fit->residual.mean_mm},
                                            {"max", r.league_fit->residual.max_mm}}}};
    }
    const auto& m = r.measures;
    j["measures"] = {{"overlap_ratio", m.overlap_ratio},         {"mean_distance_px", m.mean_distance_px},
                     {"mean_distance_mm", m.mean_distance_mm},   {"line_pixels", m.line_pixels},
                     {"matched_pixels", m.matched_pixels},       {"model_support", m.model_support}};
  }
  if (r.symmetry) {
    const auto& s = *r.symmetry;
    j["symmetry"] = {{"basis", s.basis},
                     {"decided", s.decided},
                     {"reason", s.reason},
                     {"position_mm", xyz(s.position)},
                     {"view_mm", xy(s.view)},
                     {"alternative_position_mm", xyz(s.alternative_position)},
                     {"alternative_view_mm", xy(s.alternative_view)},
                     {"text", s.describe()}};
  }
  return j;
}

}  // namespace dv

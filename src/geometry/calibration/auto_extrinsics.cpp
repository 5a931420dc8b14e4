#include "geometry/calibration/auto_extrinsics.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "geometry/calibration/line_fit.h"
#include "geometry/calibration/point_pose.h"

namespace dv {

namespace {

// A straight image line in undistorted pixels: n . p = rho, n = (cos t, sin t).
struct ImageLine {
  double theta = 0, rho = 0;
  double extent = 0;
  cv::Point2d mid;
};

std::optional<ImageLine> fitImageLine(const LineGroup& g, const PixelDistortion& d) {
  if (g.pixels.size() < 20) return std::nullopt;
  std::vector<cv::Point2d> pts;
  for (const auto& p : g.pixels) {
    const ImagePx u = d.undistort(p);
    pts.emplace_back(u.u, u.v);
  }
  cv::Vec4d l;
  cv::fitLine(pts, l, cv::DIST_HUBER, 0, 0.01, 0.01);
  ImageLine out;
  out.theta = std::atan2(l[0], -l[1]);  // normal of direction (l0, l1)
  const double nx = std::cos(out.theta), ny = std::sin(out.theta);
  out.rho = nx * l[2] + ny * l[3];
  double sq = 0, tmin = 1e300, tmax = -1e300;
  for (const auto& p : pts) {
    const double r = nx * p.x + ny * p.y - out.rho;
    sq += r * r;
    const double t = -ny * p.x + nx * p.y;
    tmin = std::min(tmin, t), tmax = std::max(tmax, t);
  }
  // Curved groups (the center circle) are not straight lines.
  if (std::sqrt(sq / pts.size()) > 2.0) return std::nullopt;
  out.extent = tmax - tmin;
  out.mid = cv::Point2d(l[2], l[3]);
  return out;
}

double directionDifference(const ImageLine& a, const ImageLine& b) {
  double d = std::fmod(std::abs(a.theta - b.theta), kPi);
  return std::min(d, kPi - d);
}

std::optional<cv::Point2d> intersect(const ImageLine& a, const ImageLine& b) {
  const double a1 = std::cos(a.theta), b1 = std::sin(a.theta), a2 = std::cos(b.theta), b2 = std::sin(b.theta);
  const double det = a1 * b2 - a2 * b1;
  if (std::abs(det) < 1e-6) return std::nullopt;
  return cv::Point2d((a.rho * b2 - b.rho * b1) / det, (a1 * b.rho - a2 * a.rho) / det);
}

double signedArea(const std::vector<cv::Point2d>& q) {
  double s = 0;
  for (size_t i = 0; i < q.size(); ++i) {
    const auto& a = q[i];
    const auto& b = q[(i + 1) % q.size()];
    s += a.x * b.y - b.x * a.y;
  }
  return s / 2;
}

struct Hypothesis {
  double score = 0;
  std::vector<PointCorrespondence> points;
};

}  // namespace

AutoExtrinsicsResult findPoseAutomatically(const LineObservation& obs, const PixelDistortion& dist,
                                           const FieldModel& field, const FieldRect& region, int width,
                                           int height, const AutoExtrinsicsOptions& o) {
  AutoExtrinsicsResult result;
  // 1. Straight image lines, longest first, duplicates merged.
  std::vector<ImageLine> lines;
  for (const auto& g : obs.groups) {
    const auto l = fitImageLine(g, dist);
    if (!l || l->extent < 0.08 * std::min(width, height)) continue;
    bool duplicate = false;
    for (const auto& k : lines) {
      const double dist_mid = std::abs(std::cos(k.theta) * l->mid.x + std::sin(k.theta) * l->mid.y - k.rho);
      if (directionDifference(k, *l) < 2 * kPi / 180 && dist_mid < 8) duplicate = true;
    }
    if (!duplicate) lines.push_back(*l);
    if (lines.size() >= 10) break;
  }
  if (lines.size() < 4) {
    result.reason = "fewer than four straight field lines found";
    return result;
  }

  // 2. Model lines near the camera's region: lines of constant x and of constant y.
  const double l = field.field_length / 2.0, w = field.field_width / 2.0;
  const double xp = l - field.penalty_area_depth, yp = field.penalty_area_width / 2.0;
  const double margin = 0.4 * std::max(region.x_max - region.x_min, region.y_max - region.y_min);
  std::vector<double> xs, ys;
  for (double x : {-l, -xp, 0.0, xp, l})
    if (x >= region.x_min - margin && x <= region.x_max + margin) xs.push_back(x);
  for (double y : {-w, -yp, 0.0, yp, w})
    if (y >= region.y_min - margin && y <= region.y_max + margin) ys.push_back(y);

  // Model samples near the region for scoring.
  const FieldLineModel model(field);
  std::vector<FieldMm> samples;
  for (const auto& s : model.samples(100))
    if (s.x >= region.x_min - margin && s.x <= region.x_max + margin && s.y >= region.y_min - margin &&
        s.y <= region.y_max + margin)
      samples.push_back(s);

  auto score = [&](const cv::Matx33d& H) {
    int visible = 0, hits = 0;
    for (const auto& s : samples) {
      const cv::Vec3d q = H * cv::Vec3d(s.x, s.y, 1);
      if (!(q[2] > 1e-12)) continue;
      const auto px = dist.distort({q[0] / q[2], q[1] / q[2]});
      if (!px || px->u < 2 || px->v < 2 || px->u >= width - 2 || px->v >= height - 2) continue;
      ++visible;
      if (obs.distance.at<float>(int(px->v + 0.5), int(px->u + 0.5)) <= 3.0f) ++hits;
    }
    return hits - 0.5 * (visible - hits);
  };

  // 3. Hypotheses: two image lines matched to two model lines of one family,
  // two to the other; the four crossings give a homography.
  std::vector<std::pair<int, int>> parallel_pairs;
  for (size_t i = 0; i < lines.size(); ++i)
    for (size_t j = i + 1; j < lines.size(); ++j)
      if (directionDifference(lines[i], lines[j]) < 35 * kPi / 180) parallel_pairs.push_back({int(i), int(j)});
  std::vector<Hypothesis> hyps;
  for (size_t a = 0; a < parallel_pairs.size(); ++a)
    for (size_t b = a + 1; b < parallel_pairs.size(); ++b) {
      const auto [a1, a2] = parallel_pairs[a];
      const auto [b1, b2] = parallel_pairs[b];
      if (a1 == b1 || a1 == b2 || a2 == b1 || a2 == b2) continue;
      if (directionDifference(lines[a1], lines[b1]) < 30 * kPi / 180) continue;
      const int img[4][2] = {{a1, b1}, {a2, b1}, {a2, b2}, {a1, b2}};
      std::vector<cv::Point2d> quad;
      for (const auto& c : img) {
        const auto p = intersect(lines[c[0]], lines[c[1]]);
        if (!p) break;
        quad.push_back(*p);
      }
      if (quad.size() != 4) continue;
      const double image_area = signedArea(quad);
      for (int swap = 0; swap < 2; ++swap) {
        const auto& first = swap ? ys : xs;   // values for lines a1, a2
        const auto& second = swap ? xs : ys;  // values for lines b1, b2
        for (size_t i = 0; i < first.size(); ++i)
          for (size_t j = 0; j < first.size(); ++j) {
            if (i == j) continue;
            for (size_t k = 0; k < second.size(); ++k)
              for (size_t m = 0; m < second.size(); ++m) {
                if (k == m) continue;
                // Field point of crossing (line with value v1 of `first`, v2 of `second`).
                auto fp = [&](double v1, double v2) {
                  return swap ? cv::Point2d(v2, v1) : cv::Point2d(v1, v2);
                };
                const std::vector<cv::Point2d> fq = {fp(first[i], second[k]), fp(first[j], second[k]),
                                                      fp(first[j], second[m]), fp(first[i], second[m])};
                // A camera above the field reverses the orientation from
                // field (y up) to image (v down).
                if (signedArea(fq) * image_area >= 0) continue;
                std::vector<cv::Point2f> src, dst;
                for (int c = 0; c < 4; ++c) src.emplace_back(fq[c]), dst.emplace_back(quad[c]);
                cv::Matx33d H = cv::getPerspectiveTransform(src, dst);
                const cv::Vec3d q0 = H * cv::Vec3d(fq[0].x, fq[0].y, 1);
                if (q0[2] < 0) H = -H;
                const double s = score(H);
                ++result.hypotheses;
                if (s <= 0) continue;
                Hypothesis h;
                h.score = s;
                bool ok = true;
                for (int c = 0; c < 4 && ok; ++c) {
                  const auto px = dist.distort({quad[c].x, quad[c].y});
                  if (!px) ok = false;
                  else h.points.push_back({{fq[c].x, fq[c].y, 0}, *px});
                }
                if (ok) hyps.push_back(std::move(h));
              }
          }
      }
    }
  if (hyps.empty()) {
    result.reason = "no match of image lines to the field lines";
    return result;
  }
  std::sort(hyps.begin(), hyps.end(), [](const auto& a, const auto& b) { return a.score > b.score; });

  // 4. Pose and refinement for the best few distinct hypotheses.
  struct Candidate {
    CameraParams params;
    double cost;
  };
  std::vector<Candidate> candidates;
  PointPoseOptions po;
  po.camera_height_mm = o.camera_height_mm;
  po.image_width = width, po.image_height = height;
  LineFitOptions lf;
  lf.fix_height = o.camera_height_mm.has_value();
  lf.gates_px = {24, 12, 6, 3};
  lf.max_pixels = 8000;
  int tried = 0;
  for (const auto& h : hyps) {
    if (tried >= o.max_refined_hypotheses) break;
    const auto pose = solvePointPose(h.points, dist, po);
    if (!pose || pose->rms_px > 10) continue;
    // Same pose as an earlier candidate: nothing new to learn.
    bool seen = false;
    for (const auto& c : candidates)
      if (std::hypot(c.params.position[0] - pose->params.position[0],
                     c.params.position[1] - pose->params.position[1]) < 100)
        seen = true;
    if (seen) continue;
    ++tried;
    auto fit = refineOnLines(pose->params, obs.pixels, model, {}, lf);
    candidates.push_back({fit.params, fit.cost_after});
  }
  if (candidates.empty()) {
    result.reason = "no line match gives a plausible camera pose";
    return result;
  }
  // Final polish of the best with all pixels and then the ambiguity check.
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.cost < b.cost; });
  LineFitOptions fine = lf;
  fine.gates_px = {4, 3};
  fine.max_pixels = 20000;
  const auto best = refineOnLines(candidates[0].params, obs.pixels, model, {}, fine);
  for (const auto& c : candidates)
    spdlog::debug("calibration candidate: cost {:.4f}, camera at ({:.0f}, {:.0f}, {:.0f}), f {:.1f}", c.cost,
                  c.params.position[0], c.params.position[1], c.params.position[2], c.params.intrinsics[0]);
  for (size_t i = 1; i < candidates.size(); ++i) {
    const auto& c = candidates[i];
    const double moved = std::hypot(c.params.position[0] - best.params.position[0],
                                     c.params.position[1] - best.params.position[1]);
    if (moved > 150 && c.cost < 1.15 * candidates[0].cost) {
      result.reason = "two different poses fit the lines about equally well";
      return result;
    }
  }
  result.params = best.params;
  return result;
}

}  // namespace dv

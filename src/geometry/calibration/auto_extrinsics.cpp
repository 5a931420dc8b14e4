#include "geometry/calibration/auto_extrinsics.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "geometry/calibration/centre_circle.h"
#include "geometry/calibration/field_symmetry.h"
#include "geometry/calibration/image_lines.h"
#include "geometry/calibration/line_fit.h"
#include "geometry/calibration/point_pose.h"
#include "geometry/camera_model.h"

namespace dv {

namespace {

// PixelDistortion::distort through a table over the undistorted radius
// (0.5 px steps, linear): scoring projects a million samples.
class RadialTable {
 public:
  RadialTable(const PixelDistortion& d, int width, int height) : d_(d) {
    double r_max = 0;
    for (const ImagePx c : {ImagePx{0, 0}, ImagePx{double(width), 0}, ImagePx{0, double(height)},
                            ImagePx{double(width), double(height)}}) {
      const ImagePx u = d.undistort(c);
      r_max = std::max(r_max, std::hypot(u.u - d.cx, u.v - d.cy));
    }
    scale_.resize(size_t(r_max / kStep) + 3);
    for (size_t i = 0; i < scale_.size(); ++i) {
      const double r = std::max(1e-3, i * kStep);
      const auto rd = CameraModel::distortRadius(r, d.kappa);
      scale_[i] = rd ? *rd / r : -1;
    }
  }
  // Empty beyond the image's corners or the reachable radius.
  std::optional<ImagePx> distort(double u, double v) const {
    const double dx = u - d_.cx, dy = v - d_.cy;
    const double t = std::hypot(dx, dy) / kStep;
    const size_t i = size_t(t);
    if (!(t >= 0) || i + 1 >= scale_.size() || scale_[i] < 0 || scale_[i + 1] < 0) return std::nullopt;
    const double s = scale_[i] + (t - i) * (scale_[i + 1] - scale_[i]);
    return ImagePx{d_.cx + dx * s, d_.cy + dy * s};
  }

 private:
  static constexpr double kStep = 0.5;
  PixelDistortion d_;
  std::vector<double> scale_;
};

struct Hypothesis {
  double score = 0, hit_share = 0, rank = 0;
  cv::Matx33d H;
  std::vector<PointCorrespondence> points;
};

}  // namespace

AutoExtrinsicsResult findPoseAutomatically(const LineObservation& obs, const PixelDistortion& dist,
                                           const FieldModel& field, int width, int height,
                                           const AutoExtrinsicsOptions& o) {
  AutoExtrinsicsResult result;
  // 1. Straight image lines, longest first, duplicates merged.
  std::vector<ImageLine> lines;
  for (const auto& g : obs.groups) {
    const auto l = fitImageLine(g, dist);
    if (!l || l->extent < 0.08 * std::min(width, height)) continue;
    bool duplicate = false;
    for (const auto& k : lines)
      if (directionDifference(k, *l) < 2 * kPi / 180 && k.distanceTo(l->mid) < 8) duplicate = true;
    if (!duplicate) lines.push_back(*l);
    if (lines.size() >= 10) break;
  }
  const FieldLineModel model(field);
  double circle_radius = 0;
  for (const auto& e : model.elements())
    if (e.is_arc && std::hypot(e.center.x, e.center.y) < 1 && e.a2 - e.a1 > 6) circle_radius = e.radius;
  const auto circle = circle_radius > 0 && !lines.empty()
                          ? findCentreCircle(obs, dist, lines, width, height)
                          : std::nullopt;
  spdlog::debug("straight lines {}, circle {}", lines.size(), circle.has_value());
  if (lines.size() < 4 && !circle) {
    result.reason = "fewer than four straight field lines and no centre circle found";
    return result;
  }

  // 2. Every model line of constant x and of constant y: where the camera
  // looks is found here, not assumed (the camera id only settles the
  // field's half-turn symmetry, later).
  const double l = field.field_length / 2.0, w = field.field_width / 2.0;
  const double xp = l - field.penalty_area_depth, yp = field.penalty_area_width / 2.0;
  const std::vector<double> xs = {-l, -xp, 0.0, xp, l}, ys = {-w, -yp, 0.0, yp, w};
  const std::vector<FieldMm> samples = model.samples(100);
  const RadialTable table(dist, width, height);

  // Line samples on line pixels, less half the ones in view that are not;
  // a cheap pass on every fourth sample drops hopeless matches first.
  auto score = [&](const cv::Matx33d& H, size_t stride, double* hit_share) {
    int visible = 0, hits = 0;
    for (size_t i = 0; i < samples.size(); i += stride) {
      const auto& s = samples[i];
      const cv::Vec3d q = H * cv::Vec3d(s.x, s.y, 1);
      if (!(q[2] > 1e-12)) continue;
      const auto px = table.distort(q[0] / q[2], q[1] / q[2]);
      if (!px || px->u < 2 || px->v < 2 || px->u >= width - 2 || px->v >= height - 2) continue;
      ++visible;
      if (obs.distance.at<float>(int(px->v + 0.5), int(px->u + 0.5)) <= 3.0f) ++hits;
    }
    if (hit_share) *hit_share = visible ? double(hits) / visible : 0;
    return double(stride) * (hits - 0.5 * (visible - hits));
  };
  // Share of the image's line pixels that lie on a model line under H: a
  // match that squeezes the field into a cluttered corner scores many
  // model samples but explains few of the lines seen.
  std::vector<cv::Point2d> probe;
  for (size_t i = 0; i < obs.pixels.size(); i += std::max<size_t>(1, obs.pixels.size() / 1500)) {
    const ImagePx u = dist.undistort(obs.pixels[i]);
    probe.emplace_back(u.u, u.v);
  }
  auto explained = [&](const cv::Matx33d& H) {
    const cv::Matx33d Hi = H.inv();
    int on = 0;
    for (const auto& p : probe) {
      const cv::Vec3d f = Hi * cv::Vec3d(p.x, p.y, 1);
      if (std::abs(f[2]) < 1e-12) continue;
      const FieldMm fp{f[0] / f[2], f[1] / f[2]};
      const auto near = model.nearest(fp);
      if (near.element < 0) continue;
      // Back to the image: the pixel distance to the nearest line point.
      const FieldLineElement& e = model.elements()[near.element];
      FieldMm q = fp;
      if (e.is_arc) {
        const double r = std::hypot(fp.x - e.center.x, fp.y - e.center.y);
        if (r > 1e-9) q = {e.center.x + (fp.x - e.center.x) * e.radius / r, e.center.y + (fp.y - e.center.y) * e.radius / r};
      } else {
        const double dx = e.b.x - e.a.x, dy = e.b.y - e.a.y, len2 = dx * dx + dy * dy;
        const double t = std::clamp(((fp.x - e.a.x) * dx + (fp.y - e.a.y) * dy) / len2, 0.0, 1.0);
        q = {e.a.x + t * dx, e.a.y + t * dy};
      }
      const cv::Vec3d b = H * cv::Vec3d(q.x, q.y, 1);
      if (!(b[2] > 1e-12)) continue;
      if (std::hypot(b[0] / b[2] - p.x, b[1] / b[2] - p.y) <= 6) ++on;
    }
    return probe.empty() ? 0.0 : double(on) / probe.size();
  };
  std::vector<Hypothesis> hyps;
  // Field quad -> undistorted image quad.
  auto consider = [&](const std::vector<cv::Point2d>& fq, const std::vector<cv::Point2d>& quad) {
    std::vector<cv::Point2f> src, dst;
    for (int c = 0; c < 4; ++c) src.emplace_back(fq[c]), dst.emplace_back(quad[c]);
    cv::Matx33d H = cv::getPerspectiveTransform(src, dst);
    const cv::Vec3d q0 = H * cv::Vec3d(fq[0].x, fq[0].y, 1);
    if (q0[2] < 0) H = -H;
    ++result.hypotheses;
    if (score(H, 4, nullptr) <= 0) return;
    Hypothesis h;
    h.score = score(H, 1, &h.hit_share);
    if (h.score <= 0) return;
    h.H = H;
    for (int c = 0; c < 4; ++c) {
      const auto px = dist.distort({quad[c].x, quad[c].y});
      if (!px) return;
      h.points.push_back({{fq[c].x, fq[c].y, 0}, *px});
    }
    hyps.push_back(std::move(h));
  };

  // 3a. Two image lines matched to two model lines of one family, two to
  // the other; the four crossings give a homography.
  std::vector<std::pair<int, int>> parallel_pairs;
  for (size_t i = 0; i < lines.size(); ++i)
    for (size_t j = i + 1; j < lines.size(); ++j)
      if (directionDifference(lines[i], lines[j]) < 35 * kPi / 180) parallel_pairs.push_back({int(i), int(j)});
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
        auto fp = [&](double v1, double v2) { return swap ? cv::Point2d(v2, v1) : cv::Point2d(v1, v2); };
        for (size_t i = 0; i < first.size(); ++i)
          for (size_t j = 0; j < first.size(); ++j) {
            if (i == j) continue;
            for (size_t k = 0; k < second.size(); ++k)
              for (size_t m = 0; m < second.size(); ++m) {
                if (k == m) continue;
                const std::vector<cv::Point2d> fq = {fp(first[i], second[k]), fp(first[j], second[k]),
                                                      fp(first[j], second[m]), fp(first[i], second[m])};
                // A camera above the field reverses the orientation from
                // field (y up) to image (v down). Of a half-turn pair only
                // one is tried: the twin is decided later.
                if (signedArea(fq) * image_area >= 0) continue;
                if (fq[0].x + fq[2].x < 0 || (fq[0].x + fq[2].x == 0 && fq[0].y + fq[2].y < 0)) continue;
                consider(fq, quad);
              }
          }
      }
    }
  // 3b. The centre circle and the halfway line.
  if (circle)
    for (const auto& pts : centreCircleHypotheses(*circle, lines, dist, circle_radius)) {
      std::vector<cv::Point2d> fq, quad;
      for (const auto& p : pts) {
        const ImagePx u = dist.undistort(p.image);
        fq.emplace_back(p.field.x, p.field.y), quad.emplace_back(u.u, u.v);
      }
      consider(fq, quad);
    }
  if (hyps.empty()) {
    result.reason = "no match of image lines to the field lines";
    return result;
  }
  std::sort(hyps.begin(), hyps.end(), [](const auto& a, const auto& b) { return a.score > b.score; });
  // The best by samples, re-ranked by how much of both the model in view
  // and the lines seen they explain.
  if (hyps.size() > size_t(o.reranked_hypotheses)) hyps.resize(size_t(o.reranked_hypotheses));
  for (auto& h : hyps) h.rank = h.hit_share * explained(h.H);
  std::sort(hyps.begin(), hyps.end(), [](const auto& a, const auto& b) { return a.rank > b.rank; });

  // 4. Pose and refinement for the best few distinct hypotheses.
  struct Candidate {
    CameraParams params;
    double cost;
  };
  // Distance between two poses' camera centres, the half turn counted as
  // the same pose.
  auto apart = [](const CameraParams& a, const CameraParams& b) {
    return std::min(std::hypot(a.position[0] - b.position[0], a.position[1] - b.position[1]),
                    std::hypot(a.position[0] + b.position[0], a.position[1] + b.position[1]));
  };
  std::vector<Candidate> candidates;
  PointPoseOptions po;
  po.camera_height_mm = o.camera_height_mm;
  po.image_width = width, po.image_height = height;
  LineFitOptions lf;
  lf.fix_height = o.camera_height_mm.has_value();
  lf.gates_px = {24, 12, 6, 3};
  lf.max_pixels = 3000;  // enough to rank the candidates; the polish takes 20000
  std::vector<CameraParams> starts;
  for (const auto& h : hyps) {
    if (int(starts.size()) >= o.max_refined_hypotheses) break;
    const auto pose = solvePointPose(h.points, dist, po);
    if (!pose || pose->rms_px > 10) continue;
    // A camera the quality gate would refuse for its height is not worth refining.
    if (!(pose->params.position[2] > 300 && pose->params.position[2] < 30000)) continue;
    // Same pose as an earlier start: nothing new to learn.
    bool seen = false;
    for (const auto& c : starts)
      if (apart(c, pose->params) < 100) seen = true;
    if (!seen) starts.push_back(pose->params);
  }
  // The refinements are independent: one thread each (the cores share them).
  std::vector<std::future<LineFitResult>> fits;
  for (const auto& start : starts)
    fits.push_back(std::async(std::launch::async, [&, start] { return refineOnLines(start, obs.pixels, model, {}, lf); }));
  for (auto& f : fits) {
    const LineFitResult fit = f.get();
    candidates.push_back({fit.params, fit.cost_after});
  }
  if (candidates.empty()) {
    result.reason = "no line match gives a plausible camera pose";
    return result;
  }
  // Final polish of the best and of every other that fits about as well
  // (unless it is the best's twin).
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.cost < b.cost; });
  for (const auto& c : candidates)
    spdlog::debug("calibration candidate: cost {:.4f}, camera at ({:.0f}, {:.0f}, {:.0f}), f {:.1f}", c.cost,
                  c.params.position[0], c.params.position[1], c.params.position[2], c.params.intrinsics[0]);
  LineFitOptions fine = lf;
  fine.gates_px = {4, 3};
  fine.max_pixels = 20000;
  for (const auto& c : candidates) {
    if (c.cost > 1.15 * candidates[0].cost) break;
    bool known = false;
    for (const auto& r : result.readings)
      if (apart(r, c.params) < 150) known = true;
    if (!known) result.readings.push_back(refineOnLines(c.params, obs.pixels, model, {}, fine).params);
  }
  return result;
}

}  // namespace dv

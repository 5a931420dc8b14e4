#include "geometry/calibration/calibration_quality.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace dv {

cv::Mat lineDistanceTransform(const cv::Mat& line_mask) {
  cv::Mat inverted, dist;
  cv::bitwise_not(line_mask, inverted);
  cv::distanceTransform(inverted, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return dist;
}

CalibrationMeasures measureCalibration(const CameraCalibration& c, const FieldModel& field,
                                       const std::vector<ImagePx>& pixels,
                                       const cv::Mat& line_distance, double gate_px) {
  const CameraModel cam(c);
  const FieldLineModel model(field);
  CalibrationMeasures m;
  m.line_pixels = int(pixels.size());
  int on_line = 0;
  double sum_px = 0, sum_mm = 0;
  for (const auto& px : pixels) {
    const auto a = cam.imageToField(px, 0);
    const auto b = cam.imageToField({px.u + 1, px.v}, 0);
    const auto d = cam.imageToField({px.u, px.v + 1}, 0);
    if (!a || !b || !d) continue;
    const double scale = 0.5 * (std::hypot(b->x - a->x, b->y - a->y) + std::hypot(d->x - a->x, d->y - a->y));
    const auto near = model.nearest(a->xy());
    if (near.element < 0) continue;
    const double half = model.elements()[near.element].half_thickness;
    // On the painted line, give or take the pixel the ridge may spill into.
    if (near.distance <= half + scale) ++on_line;
    if (near.distance / scale <= gate_px) {
      ++m.matched_pixels;
      sum_px += near.distance / scale;
      sum_mm += near.distance;
    }
  }
  if (m.line_pixels > 0) m.overlap_ratio = double(on_line) / m.line_pixels;
  if (m.matched_pixels > 0) {
    m.mean_distance_px = sum_px / m.matched_pixels;
    m.mean_distance_mm = sum_mm / m.matched_pixels;
  }
  if (!line_distance.empty()) {
    int supported = 0;
    for (const auto& s : model.samples(25)) {
      const auto px = cam.fieldToImage({s.x, s.y, 0});
      if (!px) continue;
      const int u = int(std::lround(px->u)), v = int(std::lround(px->v));
      if (u < 4 || v < 4 || u >= line_distance.cols - 4 || v >= line_distance.rows - 4) continue;
      ++m.model_samples_in_view;
      if (line_distance.at<float>(v, u) <= 3.0f) ++supported;
    }
    if (m.model_samples_in_view > 0) m.model_support = double(supported) / m.model_samples_in_view;
  }
  return m;
}

std::optional<std::string> qualityProblem(const CameraCalibration& c, const CalibrationMeasures& m,
                                          const QualityGateOptions& o) {
  char buf[256];
  const CameraModel cam(c);
  const Eigen::Vector3d& pos = cam.position();
  if (!std::isfinite(c.focal_length) || c.focal_length <= 0)
    return std::string("focal length is not positive");
  if (!(pos.z() >= 500 && pos.z() <= 20000)) {
    std::snprintf(buf, sizeof buf, "implausible camera height %.0f mm", pos.z());
    return std::string(buf);
  }
  // Optical axis in field coordinates must point down.
  const Eigen::Vector3d axis = cam.rotation().transpose() * Eigen::Vector3d(0, 0, 1);
  const double tilt = std::acos(std::clamp(-axis.z(), -1.0, 1.0));
  if (tilt > 75 * kPi / 180) {
    std::snprintf(buf, sizeof buf, "implausible tilt %.0f deg from straight down", tilt * 180 / kPi);
    return std::string(buf);
  }
  if (c.image_width > 0 && c.image_height > 0) {
    if (c.principal_point_x < 0 || c.principal_point_x > c.image_width || c.principal_point_y < 0 ||
        c.principal_point_y > c.image_height)
      return std::string("principal point outside the image");
    if (c.focal_length < 0.1 * c.image_width || c.focal_length > 20.0 * c.image_width)
      return std::string("implausible focal length");
  }
  if (std::abs(c.distortion) > 2) return std::string("implausible distortion");
  if (o.region && c.image_width > 0) {
    const auto center = cam.fieldToImage(
        {(o.region->x_min + o.region->x_max) / 2, (o.region->y_min + o.region->y_max) / 2, 0});
    if (!center || center->u < 0 || center->v < 0 || center->u >= c.image_width ||
        center->v >= c.image_height)
      return std::string("the center of the camera's field region is not in view");
  }
  if (m.model_samples_in_view < o.min_model_samples) return std::string("too few field lines in view");
  if (m.overlap_ratio < o.min_overlap_ratio) {
    std::snprintf(buf, sizeof buf, "field-line overlap %.2f below %.2f", m.overlap_ratio, o.min_overlap_ratio);
    return std::string(buf);
  }
  if (m.mean_distance_px > o.max_mean_distance_px) {
    std::snprintf(buf, sizeof buf, "mean line distance %.2f px above %.2f px", m.mean_distance_px,
                  o.max_mean_distance_px);
    return std::string(buf);
  }
  if (m.model_support < o.min_model_support) {
    std::snprintf(buf, sizeof buf, "only %.0f%% of the model lines in view are seen in the image",
                  100 * m.model_support);
    return std::string(buf);
  }
  return std::nullopt;
}

double meanFieldPositionError(const CameraCalibration& reference, const CameraCalibration& other,
                              double height, const FieldRect& area, int step, int* samples) {
  const CameraModel a(reference), b(other);
  const int w = reference.image_width ? int(reference.image_width) : 2448;
  const int h = reference.image_height ? int(reference.image_height) : 2048;
  double sum = 0;
  int n = 0;
  for (int v = step / 2; v < h; v += step)
    for (int u = step / 2; u < w; u += step) {
      const auto p = a.imageToField({double(u), double(v)}, height);
      if (!p || !area.contains(p->xy())) continue;
      const auto q = b.imageToField({double(u), double(v)}, height);
      if (!q) {
        sum += 1e4;
      } else {
        sum += std::hypot(p->x - q->x, p->y - q->y);
      }
      ++n;
    }
  if (samples) *samples = n;
  return n ? sum / n : 0;
}

cv::Mat drawModelOverlay(const cv::Mat& bgr, const CameraCalibration& c, const FieldModel& field) {
  cv::Mat out = bgr.clone();
  const CameraModel cam(c);
  const FieldLineModel model(field);
  for (const auto& e : model.elements()) {
    std::vector<FieldMm> pts;
    const int n = 200;
    for (int i = 0; i <= n; ++i) {
      const double t = double(i) / n;
      if (e.is_arc) {
        const double a = e.a1 + t * (e.a2 - e.a1);
        pts.push_back({e.center.x + e.radius * std::cos(a), e.center.y + e.radius * std::sin(a)});
      } else {
        pts.push_back({e.a.x + t * (e.b.x - e.a.x), e.a.y + t * (e.b.y - e.a.y)});
      }
    }
    std::optional<ImagePx> prev;
    for (const auto& p : pts) {
      const auto px = cam.fieldToImage({p.x, p.y, 0});
      if (px && prev)
        cv::line(out, cv::Point2d(prev->u, prev->v), cv::Point2d(px->u, px->v), cv::Scalar(255, 0, 255), 1,
                 cv::LINE_AA);
      prev = px;
    }
  }
  return out;
}

}  // namespace dv

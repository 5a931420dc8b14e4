#include "app/console_image.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "app/debug_views.h"

namespace dv::app {

namespace {

cv::Point toPoint(double u, double v, double scale) {
  return {static_cast<int>(std::lround(u * scale)), static_cast<int>(std::lround(v * scale))};
}

// Each painted line and arc sampled every ~50 mm and projected; breaks
// where a point does not reach the image.
void drawFieldLines(cv::Mat& img, const CameraModel& cam, const FieldModel& field, double scale) {
  const cv::Scalar color(255, 0, 255);
  auto polyline = [&](const std::vector<FieldMm>& pts) {
    std::optional<cv::Point> prev;
    for (const FieldMm& p : pts) {
      const auto px = cam.fieldToImage({p.x, p.y, 0});
      if (!px) {
        prev.reset();
        continue;
      }
      const cv::Point q = toPoint(px->u, px->v, scale);
      if (prev) cv::line(img, *prev, q, color, 1, cv::LINE_AA);
      prev = q;
    }
  };
  for (const FieldLine& l : field.lines) {
    const double len = std::hypot(l.p2.x - l.p1.x, l.p2.y - l.p1.y);
    const int n = std::max(2, static_cast<int>(len / 50) + 1);
    std::vector<FieldMm> pts;
    for (int i = 0; i <= n; ++i) {
      const double t = double(i) / n;
      pts.push_back({l.p1.x + t * (l.p2.x - l.p1.x), l.p1.y + t * (l.p2.y - l.p1.y)});
    }
    polyline(pts);
  }
  for (const FieldArc& a : field.arcs) {
    const double span = a.a2 - a.a1;
    const int n = std::max(8, static_cast<int>(std::abs(span) * a.radius / 50) + 1);
    std::vector<FieldMm> pts;
    for (int i = 0; i <= n; ++i) {
      const double t = a.a1 + span * i / n;
      pts.push_back({a.center.x + a.radius * std::cos(t), a.center.y + a.radius * std::sin(t)});
    }
    polyline(pts);
  }
}

// The heading is the point 120 mm ahead at the robot's height, projected.
void drawDetections(cv::Mat& img, const ssl::SSL_DetectionFrame& d, const CameraModel* cam, double scale) {
  const int radius = std::max(4, static_cast<int>(std::lround(img.cols / 90.0)));
  auto robots = [&](const auto& list, const cv::Scalar& color) {
    for (const auto& r : list) {
      const cv::Point c = toPoint(r.pixel_x(), r.pixel_y(), scale);
      cv::circle(img, c, radius, color, 2, cv::LINE_AA);
      if (cam && r.has_orientation()) {
        const auto tip = cam->fieldToImage({r.x() + 120 * std::cos(r.orientation()),
                                            r.y() + 120 * std::sin(r.orientation()), r.height()});
        if (tip) cv::line(img, c, toPoint(tip->u, tip->v, scale), color, 2, cv::LINE_AA);
      }
      if (r.has_robot_id())
        cv::putText(img, std::to_string(r.robot_id()), c + cv::Point(radius + 2, radius / 2),
                    cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    }
  };
  robots(d.robots_yellow(), cv::Scalar(0, 230, 255));
  robots(d.robots_blue(), cv::Scalar(255, 120, 0));
  for (const auto& b : d.balls())
    cv::circle(img, toPoint(b.pixel_x(), b.pixel_y(), scale), std::max(3, radius / 2), cv::Scalar(0, 128, 255), 2,
               cv::LINE_AA);
}

}  // namespace

std::optional<SnapshotLayers> parseSnapshotLayers(const std::string& text, std::string& why) {
  SnapshotLayers l;
  std::stringstream ss(text);
  std::string name;
  while (std::getline(ss, name, ',')) {
    if (name == "raw" || name.empty()) continue;
    if (name == "lines") l.lines = true;
    else if (name == "detections") l.detections = true;
    else {
      why = "unknown layer '" + name + "' (known: raw, lines, detections; several joined by ',')";
      return std::nullopt;
    }
  }
  return l;
}

cv::Mat renderSnapshot(const Frame& frame, const ssl::SSL_DetectionFrame& detection,
                       const CameraCalibration* calibration, const FieldModel& field, const SnapshotLayers& layers,
                       int max_width) {
  const cv::Mat bgr = frameToBgr(frame);
  cv::Mat img;
  double scale = 1;
  if (max_width > 0 && bgr.cols > max_width) {
    scale = double(max_width) / bgr.cols;
    cv::resize(bgr, img, cv::Size(max_width, std::max(1, static_cast<int>(std::lround(bgr.rows * scale)))), 0, 0,
               cv::INTER_AREA);
  } else {
    img = bgr;
  }
  std::optional<CameraModel> cam;
  if (calibration) cam.emplace(*calibration);
  if (layers.lines && cam) drawFieldLines(img, *cam, field, scale);
  if (layers.detections) drawDetections(img, detection, cam ? &*cam : nullptr, scale);
  return img;
}

std::vector<FieldMm> cameraFootprint(const CameraCalibration& calibration) {
  std::vector<FieldMm> out;
  const double w = calibration.image_width, h = calibration.image_height;
  if (w <= 0 || h <= 0) return out;
  const CameraModel cam(calibration);
  constexpr int kPerEdge = 8;
  const ImagePx corners[5] = {{0, 0}, {w, 0}, {w, h}, {0, h}, {0, 0}};
  for (int e = 0; e < 4; ++e)
    for (int i = 0; i < kPerEdge; ++i) {
      const double t = double(i) / kPerEdge;
      const ImagePx px{corners[e].u + t * (corners[e + 1].u - corners[e].u),
                       corners[e].v + t * (corners[e + 1].v - corners[e].v)};
      if (const auto p = cam.imageToField(px, 0)) out.push_back(p->xy());
    }
  return out;
}

}  // namespace dv::app

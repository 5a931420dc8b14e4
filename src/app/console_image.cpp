#include "app/console_image.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "app/debug_views.h"

namespace dv::app {

namespace {

// Where a camera pixel, a grid cell or a field point lands on the picture
// being drawn: the camera image or the rectified grid, scaled by `scale`
// (a resize maps input pixel centers x to (x + 0.5) * scale - 0.5).
class View {
 public:
  View(const SnapshotSource& s, bool on_grid, double scale)
      : on_grid_(on_grid), scale_(scale), grid_(s.grid), plane_height_(s.plane_height) {
    if (s.calibration) cam_.emplace(*s.calibration);
  }
  bool hasCamera() const { return cam_.has_value(); }
  std::optional<cv::Point> ofImage(ImagePx px) const {
    if (!on_grid_) return scaled(px.u, px.v);
    if (!cam_ || !grid_) return std::nullopt;
    const auto f = cam_->imageToField(px, plane_height_);
    if (!f) return std::nullopt;
    const GridPx g = grid_->toGrid(f->xy());
    return scaled(g.x, g.y);
  }
  std::optional<cv::Point> ofGrid(GridPx g) const {
    if (on_grid_) return scaled(g.x, g.y);
    if (!cam_ || !grid_) return std::nullopt;
    const FieldMm f = grid_->toField(g);
    const auto px = cam_->fieldToImage({f.x, f.y, plane_height_});
    if (!px) return std::nullopt;
    return scaled(px->u, px->v);
  }
  std::optional<cv::Point> ofField(const FieldPoint& p) const {
    if (!cam_) return std::nullopt;
    const auto px = cam_->fieldToImage(p);
    if (!px) return std::nullopt;
    return ofImage(*px);
  }

 private:
  std::optional<cv::Point> scaled(double x, double y) const {
    return cv::Point(static_cast<int>(std::lround((x + 0.5) * scale_ - 0.5)),
                     static_cast<int>(std::lround((y + 0.5) * scale_ - 0.5)));
  }
  bool on_grid_;
  double scale_;
  std::optional<CameraModel> cam_;
  std::optional<RectifiedGrid> grid_;
  double plane_height_;
};

// Each painted line and arc sampled every ~50 mm and projected; breaks
// where a point does not reach the picture.
void drawFieldLines(cv::Mat& img, const View& view, const FieldModel& field) {
  const cv::Scalar color(255, 0, 255);
  auto polyline = [&](const std::vector<FieldMm>& pts) {
    std::optional<cv::Point> prev;
    for (const FieldMm& p : pts) {
      const auto q = view.ofField({p.x, p.y, 0});
      if (q && prev) cv::line(img, *prev, *q, color, 1, cv::LINE_AA);
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
    const double span = a.span();
    const int n = std::max(8, static_cast<int>(span * a.radius / 50) + 1);
    std::vector<FieldMm> pts;
    for (int i = 0; i <= n; ++i) {
      const double t = a.a1 + span * i / n;
      pts.push_back({a.center.x + a.radius * std::cos(t), a.center.y + a.radius * std::sin(t)});
    }
    polyline(pts);
  }
}

// The heading is the point 120 mm ahead at the robot's height, projected.
void drawDetections(cv::Mat& img, const ssl::SSL_DetectionFrame& d, const View& view) {
  const int radius = std::max(4, static_cast<int>(std::lround(img.cols / 90.0)));
  auto robots = [&](const auto& list, const cv::Scalar& color) {
    for (const auto& r : list) {
      const auto c = view.ofImage({r.pixel_x(), r.pixel_y()});
      if (!c) continue;
      cv::circle(img, *c, radius, color, 2, cv::LINE_AA);
      if (r.has_orientation()) {
        const auto tip = view.ofField({r.x() + 120 * std::cos(r.orientation()),
                                       r.y() + 120 * std::sin(r.orientation()), r.height()});
        if (tip) cv::line(img, *c, *tip, color, 2, cv::LINE_AA);
      }
      if (r.has_robot_id())
        cv::putText(img, std::to_string(r.robot_id()), *c + cv::Point(radius + 2, radius / 2),
                    cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    }
  };
  robots(d.robots_yellow(), cv::Scalar(0, 230, 255));
  robots(d.robots_blue(), cv::Scalar(255, 120, 0));
  for (const auto& b : d.balls())
    if (const auto c = view.ofImage({b.pixel_x(), b.pixel_y()}))
      cv::circle(img, *c, std::max(3, radius / 2), cv::Scalar(0, 128, 255), 2, cv::LINE_AA);
}

// Blobs filled with their mean color in a white ring; weak peaks as thin
// gray rings; fast-ball streaks in orange rings.
void drawBlobs(cv::Mat& img, const BlobList& blobs, const View& view) {
  const int radius = std::max(3, static_cast<int>(std::lround(img.cols / 160.0)));
  for (const Blob& b : blobs.weak)
    if (const auto c = view.ofGrid(b.grid)) cv::circle(img, *c, radius, cv::Scalar(170, 170, 170), 1, cv::LINE_AA);
  for (const Blob& b : blobs.blobs) {
    const auto c = view.ofGrid(b.grid);
    if (!c) continue;
    if (b.streak) {
      cv::circle(img, *c, radius + 2, cv::Scalar(0, 128, 255), 2, cv::LINE_AA);
      continue;
    }
    cv::circle(img, *c, radius, cv::Scalar(b.rgb[2], b.rgb[1], b.rgb[0]), -1, cv::LINE_AA);
    cv::circle(img, *c, radius + 1, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
}

struct LayerName {
  const char* name;
  std::optional<SnapshotBase> base;  // none: an overlay
};
constexpr LayerName kLayers[] = {{"raw", SnapshotBase::Raw},           {"rectified", SnapshotBase::Rectified},
                                 {"chroma", SnapshotBase::Chroma},     {"gradient", SnapshotBase::Gradient},
                                 {"score", SnapshotBase::Score},       {"blobs", std::nullopt},
                                 {"lines", std::nullopt},              {"detections", std::nullopt}};

}  // namespace

std::optional<SnapshotLayers> parseSnapshotLayers(const std::string& text, std::string& why) {
  SnapshotLayers l;
  std::optional<std::string> base_name;
  std::stringstream ss(text);
  std::string name;
  while (std::getline(ss, name, ',')) {
    if (name.empty()) continue;
    const LayerName* known = nullptr;
    for (const LayerName& k : kLayers)
      if (name == k.name) known = &k;
    if (!known) {
      why = "unknown layer '" + name +
            "' (known: raw, rectified, chroma, gradient, score, blobs, lines, detections; several joined by ',')";
      return std::nullopt;
    }
    if (known->base) {
      if (base_name && *base_name != name) {
        why = "layers '" + *base_name + "' and '" + name +
              "' are both pictures: choose one of raw, rectified, chroma, gradient, score";
        return std::nullopt;
      }
      base_name = name;
      l.base = *known->base;
    } else if (name == "blobs") {
      l.blobs = true;
    } else if (name == "lines") {
      l.lines = true;
    } else {
      l.detections = true;
    }
  }
  return l;
}

cv::Mat renderSnapshot(const SnapshotSource& source, const FieldModel& field, const SnapshotLayers& layers,
                       int max_width) {
  cv::Mat base;
  if (!layers.onGrid()) {
    base = frameToBgr(source.frame);
  } else if (source.grid_picture.channels() == 1) {
    cv::cvtColor(source.grid_picture, base, cv::COLOR_GRAY2BGR);
  } else {
    base = source.grid_picture.clone();
  }
  cv::Mat img;
  double scale = 1;
  if (max_width > 0 && base.cols > max_width) {
    scale = double(max_width) / base.cols;
    cv::resize(base, img, cv::Size(max_width, std::max(1, static_cast<int>(std::lround(base.rows * scale)))), 0, 0,
               cv::INTER_AREA);
  } else {
    img = base;
  }
  const View view(source, layers.onGrid(), scale);
  if (layers.lines && view.hasCamera()) drawFieldLines(img, view, field);
  if (layers.blobs) drawBlobs(img, source.blobs, view);
  if (layers.detections) drawDetections(img, source.detection, view);
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

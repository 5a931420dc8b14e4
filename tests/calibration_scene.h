#pragma once
// Test helper: draws a field image through a known camera, the way the
// calibration tests need it without the full renderer: green carpet inside
// the walls, dark outside, anti-aliased white lines of the model's thickness,
// optional robots as clutter and sensor noise.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "geometry/calibration/field_line_model.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"

namespace dv::testing {

struct SceneOptions {
  double noise_sigma = 3;
  int robots = 0;
  unsigned seed = 1;
};

// Camera at `position` looking along the direction given by yaw (rotation of
// the image's "up" about the vertical) and tilt (from straight down, towards
// the image top).
inline CameraCalibration makeCamera(uint32_t id, int width, int height, double focal, double k,
                                    double cx, double cy, Eigen::Vector3d position, double yaw,
                                    double tilt) {
  // Straight down: camera x = field x, camera y = -field y, camera z = -field z.
  Eigen::Matrix3d down;
  down << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  const Eigen::Matrix3d r = Eigen::AngleAxisd(-tilt, Eigen::Vector3d::UnitX()).toRotationMatrix() * down *
                            Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  CameraCalibration c = CameraCalibration::fromPose(id, focal, cx, cy, k, r, position);
  c.image_width = uint32_t(width);
  c.image_height = uint32_t(height);
  return c;
}

inline cv::Mat renderFieldImage(const CameraCalibration& c, const FieldModel& field,
                                const SceneOptions& o = {}) {
  const int w = int(c.image_width), h = int(c.image_height);
  const CameraModel cam(c);
  const FieldLineModel model(field);
  const FieldRect carpet = field.withBoundary();
  cv::Mat img(h, w, CV_8UC3);
  std::vector<FieldMm> robots;
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> ux(-field.field_length / 2.0, field.field_length / 2.0);
  std::uniform_real_distribution<double> uy(-field.field_width / 2.0, field.field_width / 2.0);
  for (int i = 0; i < o.robots; ++i) robots.push_back({ux(rng), uy(rng)});
  for (int v = 0; v < h; ++v) {
    cv::Vec3b* row = img.ptr<cv::Vec3b>(v);
    std::optional<FieldPoint> prev;
    for (int u = 0; u < w; ++u) {
      const auto p = cam.imageToField({double(u), double(v)}, 0);
      cv::Vec3f colour(30, 30, 30);  // beyond the walls
      if (p && carpet.contains(p->xy())) {
        colour = cv::Vec3f(40, 110, 50);
        const auto q = cam.imageToField({double(u), double(v) + 1}, 0);
        double scale = 3;
        if (prev && q)
          scale = 0.5 * (std::hypot(p->x - prev->x, p->y - prev->y) + std::hypot(p->x - q->x, p->y - q->y));
        const auto near = model.nearest(p->xy());
        const double half = model.elements()[near.element].half_thickness;
        const double cover = std::clamp((half - near.distance) / scale + 0.5, 0.0, 1.0);
        colour = colour * float(1 - cover) + cv::Vec3f(220, 225, 225) * float(cover);
        for (const auto& r : robots) {
          const double d = std::hypot(p->x - r.x, p->y - r.y);
          if (d < 90) colour = cv::Vec3f(20, 20, 20);
          if (d < 25) colour = cv::Vec3f(200, 120, 30);
          if (std::hypot(p->x - r.x - 50, p->y - r.y - 30) < 20) colour = cv::Vec3f(180, 50, 220);
        }
      }
      prev = p;
      row[u] = cv::Vec3b(cv::saturate_cast<uint8_t>(colour[0]), cv::saturate_cast<uint8_t>(colour[1]),
                         cv::saturate_cast<uint8_t>(colour[2]));
    }
  }
  if (o.noise_sigma > 0) {
    cv::Mat noise(img.size(), CV_16SC3);
    cv::theRNG().state = o.seed;
    cv::randn(noise, 0, o.noise_sigma);
    cv::Mat img16;
    img.convertTo(img16, CV_16SC3);
    img16 += noise;
    img16.convertTo(img, CV_8UC3);
  }
  return img;
}

}  // namespace dv::testing

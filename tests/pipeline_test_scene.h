#pragma once
// Tiny scene painter for pipeline tests: colored discs and white lines on a
// carpet, seen by a league camera model, supersampled per pixel and mosaiced
// per Bayer site at the site's own center. Independent of the synth module so
// the pipeline can be tested on its own.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "geometry/camera_model.h"
#include "pipeline/pipeline_options.h"

namespace dv::test {

struct Color {
  double r, g, b;
};

struct Disc {
  FieldMm center;
  double radius;
  Color color;
};

// A painted band on the carpet plane (a field line), from p1 to p2.
struct Band {
  FieldMm p1, p2;
  double width;
  Color color{235, 235, 235};
};

struct PaintedScene {
  Color carpet{40, 110, 50};
  double disc_height = 150;  // discs lie on this plane
  double carpet_height = 150;  // bands and carpet drawn on this plane too
  std::vector<Disc> discs;   // later discs are drawn over earlier ones
  std::vector<Band> bands;
  double gain = 1.0;         // exposure multiplier
  double noise_sigma = 0;    // gray levels, Gaussian
  uint32_t seed = 1;
  int supersample = 4;       // per axis

  Color colorAt(FieldMm p) const {
    Color c = carpet;
    for (const auto& b : bands) {
      const double dx = b.p2.x - b.p1.x, dy = b.p2.y - b.p1.y;
      const double len2 = dx * dx + dy * dy;
      double t = len2 > 0 ? ((p.x - b.p1.x) * dx + (p.y - b.p1.y) * dy) / len2 : 0;
      t = std::clamp(t, 0.0, 1.0);
      const double ex = b.p1.x + t * dx - p.x, ey = b.p1.y + t * dy - p.y;
      if (ex * ex + ey * ey <= 0.25 * b.width * b.width) c = b.color;
    }
    for (const auto& d : discs) {
      const double ex = p.x - d.center.x, ey = p.y - d.center.y;
      if (ex * ex + ey * ey <= d.radius * d.radius) c = d.color;
    }
    return c;
  }

  // Mean color over one pixel's footprint.
  Color pixel(const CameraModel& cam, double u, double v) const {
    Color sum{0, 0, 0};
    const int n = supersample;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const ImagePx px{u - 0.5 + (i + 0.5) / n, v - 0.5 + (j + 0.5) / n};
        const auto f = cam.imageToField(px, disc_height);
        const Color c = f ? colorAt(f->xy()) : Color{10, 10, 30};  // sky
        sum.r += c.r, sum.g += c.g, sum.b += c.b;
      }
    }
    const double k = gain / (n * n);
    return {sum.r * k, sum.g * k, sum.b * k};
  }

  // CV_8UC3 BGR image, or CV_8UC1 mosaic where each site samples its own
  // channel at its own center.
  cv::Mat render(const CameraModel& cam, BayerPattern bayer) const {
    const auto& c = cam.calibration();
    const int w = static_cast<int>(c.image_width), h = static_cast<int>(c.image_height);
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, noise_sigma > 0 ? noise_sigma : 1);
    auto q = [&](double v) {
      if (noise_sigma > 0) v += noise(rng);
      return cv::saturate_cast<uint8_t>(v);
    };
    if (bayer == BayerPattern::None) {
      cv::Mat img(h, w, CV_8UC3);
      for (int v = 0; v < h; ++v)
        for (int u = 0; u < w; ++u) {
          const Color p = pixel(cam, u, v);
          img.at<cv::Vec3b>(v, u) = cv::Vec3b(q(p.b), q(p.g), q(p.r));
        }
      return img;
    }
    // Site channel: 0 = R, 1 = G, 2 = B, by pattern and parity.
    int site[2][2];
    const int rx = bayer == BayerPattern::GRBG || bayer == BayerPattern::BGGR;
    const int ry = bayer == BayerPattern::GBRG || bayer == BayerPattern::BGGR;
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) site[y][x] = 1;
    site[ry][rx] = 0;
    site[1 - ry][1 - rx] = 2;
    cv::Mat img(h, w, CV_8UC1);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        const Color p = pixel(cam, u, v);
        const int s = site[v & 1][u & 1];
        img.at<uint8_t>(v, u) = q(s == 0 ? p.r : s == 1 ? p.g : p.b);
      }
    return img;
  }
};

// A camera looking straight down from `height` mm above (cx, cy), image +u
// along field +x and +v along field -y.
inline CameraModel topDownCamera(double cx, double cy, double height, double focal, int w, int h,
                                 double distortion = 0) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  r(1, 1) = -1;
  r(2, 2) = -1;
  auto calib = CameraCalibration::fromPose(0, focal, (w - 1) / 2.0, (h - 1) / 2.0, distortion, r,
                                           Eigen::Vector3d(cx, cy, height));
  calib.image_width = w;
  calib.image_height = h;
  return CameraModel(calib);
}

// Robot pattern colors (RGB).
constexpr Color kOrange{255, 120, 20}, kYellow{230, 210, 40}, kBlue{40, 80, 200},
    kPink{240, 90, 180}, kGreen{60, 200, 80}, kBlack{25, 25, 25};

// A robot top: black disc r=90 (the largest robot) with a center blob (r=25) and four side blobs
// (r=20) at the standard positions, rotated by `angle`.
inline void addRobot(PaintedScene& s, FieldMm c, double angle, Color team, const Color sides[4]) {
  s.discs.push_back({c, 90, kBlack});
  s.discs.push_back({c, 25, team});
  const double px[4] = {35, 35, -54.772, -54.772}, py[4] = {54.772, -54.772, 35, -35};
  for (int i = 0; i < 4; ++i) {
    const double x = c.x + std::cos(angle) * px[i] - std::sin(angle) * py[i];
    const double y = c.y + std::sin(angle) * px[i] + std::cos(angle) * py[i];
    s.discs.push_back({{x, y}, 20, sides[i]});
  }
}

}  // namespace dv::test

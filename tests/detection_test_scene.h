#pragma once
// Hand-built blob lists for the detection tests: exact pattern geometry seen
// through a camera, blob positions on the pipeline's plane (z = 150 mm) with
// position noise, realistic colors under different camera looks, clutter.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "detection/detector.h"
#include "geometry/camera_model.h"
#include "geometry/robot_pattern.h"
#include "pipeline/blob.h"

namespace dv::test {

// A camera at `pos` looking at `target` (field mm), image up = field +z (or
// +y when looking straight down).
inline CameraCalibration lookAtCamera(const Eigen::Vector3d& pos, const Eigen::Vector3d& target,
                                      double focal = 900, int width = 1224, int height = 1024) {
  const Eigen::Vector3d z = (target - pos).normalized();
  Eigen::Vector3d up(0, 0, 1);
  if (std::abs(z.dot(up)) > 0.99) up = Eigen::Vector3d(0, 1, 0);
  const Eigen::Vector3d x = z.cross(up).normalized();  // image right
  const Eigen::Vector3d y = z.cross(x);                // image down
  Eigen::Matrix3d r;
  r.row(0) = x;
  r.row(1) = y;
  r.row(2) = z;
  auto c = CameraCalibration::fromPose(0, focal, width / 2.0, height / 2.0, 0, r, pos);
  c.image_width = width;
  c.image_height = height;
  return c;
}

inline CameraCalibration topDownCamera() {
  return lookAtCamera({2250, 0, 4500}, {2250, 0, 0}, 700);
}

struct Look {  // how the camera renders colors
  double gain[3] = {1, 1, 1};  // white balance
  double exposure = 1;
  double saturation = 1;  // 1 = as is, 0 = gray
  double noise = 3;       // per channel, 0..255 levels
};

inline Look lookNormal() { return {}; }
inline Look lookBlueWhiteBalance() { return {{0.75, 0.95, 1.45}, 1.0, 1.0, 3}; }
inline Look lookDark() { return {{1, 1, 1}, 0.3, 1.0, 4}; }
inline Look lookDesaturated() { return {{1, 1, 1}, 0.9, 0.45, 3}; }

struct TrueRobot {
  Team team = Team::Yellow;
  int id = 0;
  FieldMm position;
  double orientation = 0;
  double height = 140;
  std::array<bool, 5> present = {true, true, true, true, true};  // center, FL, BL, BR, FR
  std::array<bool, 5> weak = {};  // present as a weak peak (BlobList::weak) only
};

class SceneBuilder {
 public:
  SceneBuilder(const CameraModel& camera, unsigned seed, Look look = {}, double pos_noise = 1.5)
      : camera_(camera), rng_(seed), look_(look), pos_noise_(pos_noise) {
    list.plane_height = 150;
  }

  static constexpr ColorRef kYellow{230, 210, 40}, kBlue{40, 80, 200}, kGreen{60, 200, 80},
      kPink{240, 90, 180}, kOrange{255, 120, 20}, kCarpet{40, 110, 50}, kWhite{235, 235, 235};

  // A blob whose true center is `p`; stored where its ray meets z = 150 (in
  // the weak peaks when `weak`).
  void addBlob(const FieldPoint& p, ColorRef rgb, float score, bool weak = false) {
    const Eigen::Vector3d c = camera_.position();
    const double s = (c.z() - list.plane_height) / (c.z() - p.z);
    std::normal_distribution<double> n(0, pos_noise_);
    Blob b;
    b.position = {c.x() + s * (p.x - c.x()) + n(rng_), c.y() + s * (p.y - c.y()) + n(rng_)};
    if (auto px = camera_.fieldToImage({b.position.x, b.position.y, list.plane_height}))
      b.grid = {px->u, px->v};
    std::uniform_real_distribution<float> sv(0.85f, 1.15f);
    b.score = score * sv(rng_);
    const ColorRef c2 = render(rgb);
    b.rgb[0] = c2.r, b.rgb[1] = c2.g, b.rgb[2] = c2.b;
    (weak ? list.weak : list.blobs).push_back(b);
  }

  void addRobot(const TrueRobot& r) {
    const auto colors = patternColors(r.id);
    const double cs = std::cos(r.orientation), sn = std::sin(r.orientation);
    if (r.present[0])
      addBlob({r.position.x, r.position.y, r.height}, r.team == Team::Yellow ? kYellow : kBlue,
              r.weak[0] ? 0.18f : 1.0f, r.weak[0]);
    for (int i = 0; i < 4; ++i) {
      if (!r.present[i + 1]) continue;
      const FieldMm o = RobotPatternGeometry::kSideBlobs[i];
      addBlob({r.position.x + cs * o.x - sn * o.y, r.position.y + sn * o.x + cs * o.y, r.height},
              colors[i] == MarkerColor::Green ? kGreen : kPink, r.weak[i + 1] ? 0.18f : 0.9f, r.weak[i + 1]);
    }
    robots.push_back(r);
  }

  void addBall(const FieldMm& p, float score = 0.8f) {
    addBlob({p.x, p.y, 21.5}, kOrange, score);
    balls.push_back(p);
  }

  // Weak carpet-colored noise blobs and white line-crossing blobs spread over
  // the area, away from robots (clutter the pipeline lets through).
  void addClutter(int carpet, int white, double x0, double x1, double y0, double y1) {
    std::uniform_real_distribution<double> ux(x0, x1), uy(y0, y1);
    for (int i = 0; i < carpet + white; ++i) {
      const FieldMm p{ux(rng_), uy(rng_)};
      bool near_robot = false;
      for (const auto& r : robots)
        near_robot |= std::hypot(p.x - r.position.x, p.y - r.position.y) < 130;
      for (const auto& b : balls) near_robot |= std::hypot(p.x - b.x, p.y - b.y) < 60;
      if (near_robot) continue;
      if (i < carpet)
        addBlob({p.x, p.y, 0}, kCarpet, 0.5f);
      else
        addBlob({p.x, p.y, 0}, kWhite, 1.0f);
    }
  }

  // Robots with distinct random ids placed at least `min_dist` apart.
  std::vector<TrueRobot> randomRobots(int yellow, int blue, double x0, double x1, double y0,
                                      double y1, double min_dist = 250) {
    std::vector<TrueRobot> out;
    std::array<int, 16> ids;
    for (int i = 0; i < 16; ++i) ids[i] = i;
    std::array<int, 16> ids_b = ids;
    std::shuffle(ids.begin(), ids.end(), rng_);
    std::shuffle(ids_b.begin(), ids_b.end(), rng_);
    std::uniform_real_distribution<double> ux(x0, x1), uy(y0, y1), ua(-kPi, kPi);
    for (int i = 0; i < yellow + blue; ++i) {
      TrueRobot r;
      r.team = i < yellow ? Team::Yellow : Team::Blue;
      r.id = i < yellow ? ids[i] : ids_b[i - yellow];
      r.orientation = ua(rng_);
      for (int attempt = 0; attempt < 1000; ++attempt) {
        r.position = {ux(rng_), uy(rng_)};
        bool ok = true;
        for (const auto& o : out)
          ok &= std::hypot(o.position.x - r.position.x, o.position.y - r.position.y) >= min_dist;
        if (ok) break;
      }
      out.push_back(r);
    }
    return out;
  }

  BlobList list;
  std::vector<TrueRobot> robots;
  std::vector<FieldMm> balls;

 private:
  ColorRef render(ColorRef c) {
    std::normal_distribution<double> n(0, look_.noise);
    double v[3] = {c.r, c.g, c.b};
    const double gray = (v[0] + v[1] + v[2]) / 3;
    for (int k = 0; k < 3; ++k) {
      v[k] = gray + look_.saturation * (v[k] - gray);
      v[k] = std::clamp(v[k] * look_.gain[k] * look_.exposure + n(rng_), 0.0, 255.0);
    }
    return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
  }

  const CameraModel& camera_;
  std::mt19937 rng_;
  Look look_;
  double pos_noise_;
};

inline double angleError(double a, double b) {
  return std::abs(std::remainder(a - b, 2 * kPi));
}

}  // namespace dv::test

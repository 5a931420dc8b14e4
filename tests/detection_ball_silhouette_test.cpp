// The ball's place from its silhouette (detection/ball_silhouette.h): from
// the touch line the blob stage puts a far ball where its score peaks on
// the sampling grid, a cell of tens of millimetres of field there (median
// error 10.8 mm on the placements below, 90 % within 24.7 mm, before the
// silhouette; 1.7 and 4.8 mm with its yes/no centroid, which leans away
// from the shaded underside; 1.1 and 2.8 mm, 95 % within 3.2 mm, with each
// sample weighed by its share of ball); top-down the peak leans to the lit
// side. Rendered
// frames, each alone, robots at their true height.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "app/camera_processor.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv {
namespace {

struct Errors {
  std::vector<double> mm;
  int missed = 0;
  double quantile(double q) const {
    std::vector<double> s = mm;
    std::sort(s.begin(), s.end());
    return s.empty() ? 1e9 : s[std::min(s.size() - 1, static_cast<size_t>(q * static_cast<double>(s.size())))];
  }
};

// The ball at each of `where`, found by the CPU's default coarse search;
// with `agree`, the full search must find it too, within 1 mm of it.
Errors ballErrors(SceneSpec spec, const std::vector<FieldMm>& where, bool agree = false) {
  spec.frames = 1;
  const std::vector<SceneRobot> robots = spec.robots;
  app::ProcessorOptions o;
  o.backend.backend = Backend::Cpu;
  o.detector.tracking = false;
  o.detector.robot_height_yellow = o.detector.robot_height_blue = 140;
  app::ProcessorOptions full = o;
  full.pipeline.coarse_search = false;
  app::CameraProcessor proc(spec.cameras[0].calib, spec.field, o), by_full(spec.cameras[0].calib, spec.field, full);
  Errors e;
  for (const FieldMm& p : where) {
    spec.ball.position = {p.x, p.y, spec.ball.position.z};
    // No robot on the ball or between it and the camera (a grazing view
    // sees the ball behind a robot's body only partly).
    const Eigen::Vector3d cam = CameraModel(spec.cameras[0].calib).position();
    spec.robots.clear();
    for (const SceneRobot& r : robots) {
      const double dx = cam.x() - p.x, dy = cam.y() - p.y, len = std::hypot(dx, dy);
      const double t = std::clamp(((r.position.x - p.x) * dx + (r.position.y - p.y) * dy) / len, 0.0, len);
      if (std::hypot(r.position.x - p.x - t * dx / len, r.position.y - p.y - t * dy / len) > 250)
        spec.robots.push_back(r);
    }
    Frame f;
    f.image = Renderer(spec).render(0, 0).image;
    f.format = PixelFormat::BayerRggb8;
    // The detected ball nearest to p, if any within 50 mm.
    auto nearest = [&](app::CameraProcessor& by) -> std::optional<FieldPoint> {
      Detections d;
      std::string why;
      if (!by.process(f, d, why)) ADD_FAILURE() << why;
      std::optional<FieldPoint> best;
      for (const auto& b : d.balls)
        if (std::hypot(b.position.x - p.x, b.position.y - p.y) < 50 &&
            (!best || std::hypot(b.position.x - p.x, b.position.y - p.y) < std::hypot(best->x - p.x, best->y - p.y)))
          best = b.position;
      return best;
    };
    const auto a = nearest(proc);
    const double err = a ? std::hypot(a->x - p.x, a->y - p.y) : -1;
    // Signed along the view (+: away from the camera) and across it.
    const double vx = p.x - cam.x(), vy = p.y - cam.y(), vl = std::hypot(vx, vy);
    const double along = a ? ((a->x - p.x) * vx + (a->y - p.y) * vy) / vl : 0;
    const double across = a ? ((a->y - p.y) * vx - (a->x - p.x) * vy) / vl : 0;
    std::printf("  ball at (%6.0f, %6.0f), %4.1f m away: error %.2f mm (%+.2f along the view, %+.2f across)\n", p.x,
                p.y, vl / 1000, err, along, across);
    if (a)
      e.mm.push_back(err);
    else
      ++e.missed;
    if (agree) {
      const auto b = nearest(by_full);
      EXPECT_EQ(a.has_value(), b.has_value()) << "coarse and full search disagree on the ball at " << p.x << ", " << p.y;
      if (a && b) {
        EXPECT_LT(std::hypot(a->x - b->x, a->y - b->y), 1.0) << "coarse vs full at " << p.x << ", " << p.y;
      }
    }
  }
  return e;
}

SceneSpec preset(const std::string& name) {
  return loadScene(std::string(DV_SOURCE_DIR) + "/config/scenes/" + name + ".yaml");
}

// The camera stands at (-1200, -3700), 1.6 m up: balls 2 to 7 m away. The
// CPU's coarse and full searches must agree on each (the coarse search lost
// the balls 5.5 and 7 m away while its fast-ball candidates were searched
// on the full grid within one lattice cell only: cpu_pipeline.cpp).
TEST(BallSilhouette, SideViewFarBallsWithinAFewMillimetres) {
  std::vector<FieldMm> where;
  for (double y = -2000; y <= 3000; y += 500)
    for (double x : {-2000.0, -900.0, 300.0}) where.push_back({x + 0.1 * y, y});
  const Errors e = ballErrors(preset("side_view"), where, /*agree=*/true);
  std::printf("side view: %zu of %zu balls, median %.2f mm, 90 %% %.2f mm, 95 %% %.2f mm\n", e.mm.size(),
              where.size(), e.quantile(0.5), e.quantile(0.9), e.quantile(0.95));
  EXPECT_EQ(e.missed, 0);
  EXPECT_LE(e.quantile(0.5), 3.0);
  EXPECT_LE(e.quantile(0.95), 4.0);
}

// Top-down under 3:1 light with a sun patch: the lit side is not the center
// (the blob's peak: median 0.85 mm, 90 % 1.44 mm on these placements; the
// silhouette's yes/no centroid 0.71 and 1.17 mm; weighed by share of ball,
// 0.42 and 0.63 mm).
TEST(BallSilhouette, TopDownUnevenLightWithinTheBar) {
  std::vector<FieldMm> where;
  for (double x = -3800; x <= -800; x += 600)
    for (double y : {-1800.0, -600.0, 600.0, 1800.0}) where.push_back({x, y});
  const Errors e = ballErrors(preset("uneven_light"), where);
  std::printf("top-down, uneven light: %zu of %zu balls, median %.2f mm, 90 %% %.2f mm\n", e.mm.size(), where.size(),
              e.quantile(0.5), e.quantile(0.9));
  EXPECT_EQ(e.missed, 0);
  EXPECT_LE(e.quantile(0.5), 0.6);
  EXPECT_LE(e.quantile(0.9), 0.9);
}

}  // namespace
}  // namespace dv

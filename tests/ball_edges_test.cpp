// The ball where searches are most likely to differ: at the image border
// (from half of it in view to whole) and at the field's edge (on the touch
// and goal lines, in the corner, between the lines and the wall), under the
// uneven-light preset (3:1 across the image, a sun patch, a shadow). The
// CPU's default coarse search, its full search and the OpenCL backend must
// agree everywhere, all find every ball at least half in the image (a ball
// cut by the border makes no blob: detection/border_balls.h), and at the
// same place: one of the independent renderer's frames had a ball by the
// touch line that only the coarse search lost.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "app/camera_processor.h"
#include "core/error.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv {
namespace {

struct Placement {
  std::string where;
  FieldMm ball;
  bool whole = true;  // the whole ball is in the image (else at least half)
};

// Ball centers at the image's four edges, k ball radii inside (k = 0: half
// of the ball in view, 0.25: 66 %, 0.5: 80 %), wherever that lies within
// the walls; and on the field's edges in view.
std::vector<Placement> placements(const SceneSpec& spec) {
  const CameraModel cam(spec.cameras[0].calib);
  const double w = spec.cameras[0].calib.image_width, h = spec.cameras[0].calib.image_height;
  const double r = spec.ball.position.z;
  const FieldModel& f = spec.field;
  // The ball's radius in pixels at the image center.
  const auto c0 = cam.fieldToImage(*cam.imageToField({w / 2, h / 2}, r));
  const FieldPoint p0 = *cam.imageToField({w / 2, h / 2}, r);
  const auto c1 = cam.fieldToImage({p0.x + r, p0.y, r});
  const double r_px = std::hypot(c1->u - c0->u, c1->v - c0->v);
  std::vector<Placement> out;
  const double half_x = f.field_length / 2 + f.boundary_width - 2 * r, half_y = f.field_width / 2 + f.boundary_width - 2 * r;
  const struct {
    const char* name;
    double u, v, du, dv;
  } edges[] = {{"left", 0, 0.4 * h, 1, 0}, {"right", w - 1, 0.6 * h, -1, 0}, {"top", 0.35 * w, 0, 0, 1},
               {"bottom", 0.65 * w, h - 1, 0, -1}};
  for (const auto& e : edges)
    for (double k : {0.0, 0.25, 0.5, 1.0, 1.5, 2.0, 3.0}) {
      const auto p = cam.imageToField({e.u + e.du * k * r_px, e.v + e.dv * k * r_px}, r);
      if (!p || std::abs(p->x) > half_x || std::abs(p->y) > half_y) continue;
      char name[64];
      std::snprintf(name, sizeof name, "image %s edge, %.1f radii in", e.name, k);
      out.push_back({name, {p->x, p->y}, k >= 1});
    }
  const double lx = f.field_length / 2, ly = f.field_width / 2;
  const Placement field_edges[] = {{"on the touch line", {-3400, ly}},
                                   {"on the other touch line", {-1500, -ly}},
                                   {"on the goal line", {-lx, -1500}},
                                   {"in the corner", {-lx + 30, ly - 30}},
                                   {"between the touch line and the wall", {-2600, ly + f.boundary_width / 2}},
                                   {"behind the goal line", {-lx - f.boundary_width / 2, 1200}}};
  for (const Placement& p : field_edges)
    if (const auto px = cam.fieldToImage({p.ball.x, p.ball.y, r});
        px && px->u > r_px && px->v > r_px && px->u < w - 1 - r_px && px->v < h - 1 - r_px)
      out.push_back(p);
  return out;
}

std::optional<FieldPoint> ballOf(app::CameraProcessor& p, const cv::Mat& image) {
  Frame f;
  f.image = image;
  f.format = PixelFormat::BayerRggb8;
  Detections d;
  std::string why;
  if (!p.process(f, d, why)) ADD_FAILURE() << why;
  if (d.balls.empty()) return std::nullopt;
  return d.balls.front().position;
}

// Runs every placement of `spec`'s camera through the three searches; each
// ball found within `max_error_mm` of its place.
void checkEdges(SceneSpec spec, size_t min_placements, double max_error_mm = 10) {
  spec.frames = 1;
  const std::vector<SceneRobot> robots = spec.robots;
  app::ProcessorOptions coarse, full, opencl;
  for (app::ProcessorOptions* o : {&coarse, &full, &opencl}) {
    o->backend.backend = Backend::Cpu;
    o->detector.tracking = false;  // each frame alone
    o->detector.robot_height_yellow = o->detector.robot_height_blue = 140;
  }
  full.pipeline.coarse_search = false;
  opencl.backend.backend = Backend::OpenCl;
  const CameraCalibration& calib = spec.cameras[0].calib;
  app::CameraProcessor by_coarse(calib, spec.field, coarse), by_full(calib, spec.field, full);
  std::optional<app::CameraProcessor> by_opencl;
  try {
    by_opencl.emplace(calib, spec.field, opencl);
  } catch (const InputError& e) {
    std::printf("  no OpenCL device (%s): the CPU searches only\n", e.what());
  }
  const std::vector<Placement> where = placements(spec);
  ASSERT_GE(where.size(), min_placements);
  int found = 0, whole = 0;
  for (const Placement& pl : where) {
    spec.ball.position = {pl.ball.x, pl.ball.y, spec.ball.position.z};
    spec.robots.clear();  // a robot standing on the ball would hide it
    for (const SceneRobot& r : robots)
      if (std::hypot(r.position.x - pl.ball.x, r.position.y - pl.ball.y) > 250) spec.robots.push_back(r);
    const cv::Mat image = Renderer(spec).render(0, 0).image;
    const auto a = ballOf(by_coarse, image), b = ballOf(by_full, image);
    const auto c = by_opencl ? ballOf(*by_opencl, image) : b;
    const double err = a ? std::hypot(a->x - pl.ball.x, a->y - pl.ball.y) : -1;
    std::printf("  %-40s (%7.1f, %7.1f): coarse %s, full %s, opencl %s; error %.2f mm\n", pl.where.c_str(), pl.ball.x,
                pl.ball.y, a ? "yes" : "NO", b ? "yes" : "NO", c ? "yes" : "NO", err);
    // All three agree everywhere and find every ball at least half in view.
    EXPECT_TRUE(a.has_value() == b.has_value() && a.has_value() == c.has_value()) << pl.where;
    EXPECT_TRUE(a && b && c) << pl.where;
    if (a && b) {
      EXPECT_LT(std::hypot(a->x - b->x, a->y - b->y), 1.0) << pl.where << ": coarse vs full";
    }
    if (a && c) {
      EXPECT_LT(std::hypot(a->x - c->x, a->y - c->y), 1.0) << pl.where << ": coarse vs OpenCL";
    }
    if (a) {
      EXPECT_LT(err, max_error_mm) << pl.where;
    }
    found += a && b && c;
    whole += pl.whole;
  }
  std::printf("  found by all three searches: %d of %zu placements (%d with the whole ball in the image, the others "
              "at least half)\n",
              found, where.size(), whole);
}

SceneSpec unevenLight() { return loadScene(std::string(DV_SOURCE_DIR) + "/config/scenes/uneven_light.yaml"); }

// The preset's camera: one image edge inside the walls, the touch lines,
// the goal line and its corners in view.
TEST(BallAtTheEdges, PresetCameraCoarseFullAndOpenClFindItAtTheSamePlace) { checkEdges(unevenLight(), 9); }

// A lower camera over the middle of the half: all four image edges on the field.
TEST(BallAtTheEdges, LowCameraCoarseFullAndOpenClFindItAtTheSamePlace) {
  SceneSpec spec = unevenLight();
  const SceneCamera& c = spec.cameras[0];
  spec.cameras = {makeCamera(0, {-1500, 300, 3500}, {-1500, 300, 0}, c.calib.focal_length, c.calib.distortion,
                             {6.5, -4.0}, static_cast<int>(c.calib.image_width), static_cast<int>(c.calib.image_height))};
  checkEdges(spec, 12);
}

// A camera on a stand at the touch line (the side-view preset): the far
// field edges see the ball 7 m away at a grazing angle, where a ball is a
// streak on the grid stretched four times along the view and a pixel spans
// 20 mm along it (between the touch line and the wall: 13.4 mm off, along
// the view; the far ball's accuracy is open work).
TEST(BallAtTheEdges, SideViewCoarseFullAndOpenClFindItAtTheSamePlace) {
  checkEdges(loadScene(std::string(DV_SOURCE_DIR) + "/config/scenes/side_view.yaml"), 8, 20);
}

}  // namespace
}  // namespace dv

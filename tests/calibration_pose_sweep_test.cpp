// Automatic calibration on poses far beyond the layout's region centers:
// cameras aimed at the centre circle, straddling the halfway line, at a
// penalty area, at a corner, the side view from beyond the touch line, and
// the layout's region centers; Division A and B, heights 3-6 m, tilts 0-45
// deg, any yaw, k -0.025..0.25, principal points up to 50 px off, 2-6 mm per
// pixel, robots and the ball in view, full 2448x2048 frames from the synth
// renderer. Each camera gets the layout id of the region it looks at, as a
// user would give it; the height only when the tool asks for it.
//
// Bars: >= 95 % within 1 mm mean field error (z = 0 and 150 mm), and no
// calibration written that is off by more than that (the table tells 1-3 mm
// from wrong beyond 3 mm); refusals name their reason. DV_SCENE_FULL=1 runs
// the full sweep (48 poses); the default is its first 12 with the same bars.
// DV_SWEEP_ONLY=i runs pose i alone with debug output.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <spdlog/spdlog.h>

#include "geometry/calibration/calibrate_camera.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv {
namespace {

constexpr int kW = 2448, kH = 2048;
enum class View { Centre, Halfway, Penalty, Corner, Side, Layout };
const char* viewName(View v) {
  switch (v) {
    case View::Centre: return "centre";
    case View::Halfway: return "halfway";
    case View::Penalty: return "penalty";
    case View::Corner: return "corner";
    case View::Side: return "side";
    case View::Layout: return "layout";
  }
  return "?";
}

struct PoseSpec {
  View view;
  bool division_a;
  FieldPoint position, aim;
  double tilt_deg, yaw_deg, k, mm_per_px;
  ImagePx pp_offset;
};

PoseSpec drawPose(View view, bool division_a, std::mt19937& rng) {
  const FieldModel f = division_a ? FieldModel::divisionA() : FieldModel::divisionB();
  const double l = f.field_length / 2.0, w = f.field_width / 2.0;
  auto U = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto sign = [&] { return U(0, 1) < 0.5 ? -1.0 : 1.0; };
  PoseSpec p;
  p.view = view, p.division_a = division_a;
  p.k = U(-0.025, 0.25);
  p.mm_per_px = U(2, 6);
  p.pp_offset = {U(-50, 50), U(-50, 50)};
  const double nice_n = division_a ? 4 : 2;
  double h = U(3000, 6000), tilt = U(0, 45), yaw = U(-180, 180);
  FieldPoint aim{0, 0, 0};
  switch (view) {
    case View::Centre: aim = {U(-300, 300), U(-300, 300), 0}; break;
    case View::Halfway: aim = {U(-300, 300), sign() * U(0.3, 0.75) * w, 0}; break;
    case View::Penalty: aim = {sign() * (l - f.penalty_area_depth / 2.0), U(-500, 500), 0}; break;
    case View::Corner: aim = {sign() * (l - U(800, 1500)), sign() * (w - U(800, 1500)), 0}; break;
    case View::Layout: {
      std::uniform_int_distribution<int> id(0, int(nice_n) - 1);
      const FieldRect r = *f.cameraRegion(uint32_t(id(rng)), unsigned(nice_n));
      aim = {(r.x_min + r.x_max) / 2, (r.y_min + r.y_max) / 2, 0};
      break;
    }
    case View::Side: {
      // Beyond the touch line, looking across the field.
      const double s = sign();
      h = U(3000, 4500);
      p.position = {U(-0.6, 0.6) * l, s * (w + f.boundary_width + U(0, 500)), h};
      aim = {p.position.x + U(-1500, 1500), s * (w - U(1500, 3000)), 0};
      const double dx = aim.x - p.position.x, dy = aim.y - p.position.y;
      tilt = std::atan2(std::hypot(dx, dy), h) * 180 / kPi;
      yaw = std::atan2(dy, dx) * 180 / kPi;
      break;
    }
  }
  if (view != View::Side) {
    const double t = tilt * kPi / 180, y = yaw * kPi / 180, back = h * std::tan(t);
    p.position = {aim.x - back * std::cos(y), aim.y - back * std::sin(y), h};
  }
  p.aim = aim, p.tilt_deg = tilt, p.yaw_deg = yaw;
  return p;
}

struct PoseResult {
  enum Kind { Within, Imprecise, Wrong, Refused } kind = Refused;
  double e0 = 0, e150 = 0, seconds = 0;
  bool height_asked = false;
  uint32_t camera_id = 0;
  std::string reason;
};

PoseResult runPose(const PoseSpec& p, uint64_t seed) {
  SceneSpec spec;
  spec.field = p.division_a ? FieldModel::divisionA() : FieldModel::divisionB();
  spec.seed = seed;
  const double t = p.tilt_deg * kPi / 180, y = p.yaw_deg * kPi / 180;
  const double distance = std::hypot(p.position.x - p.aim.x, p.position.y - p.aim.y, p.position.z);
  const FieldPoint up = t < 0.02 ? FieldPoint{std::cos(y), std::sin(y), 0} : FieldPoint{};
  SceneCamera cam = makeCamera(0, p.position, p.aim, distance / p.mm_per_px, p.k, p.pp_offset, kW, kH, up);
  const unsigned n = p.division_a ? 4 : 2;
  // The layout id of the region the camera looks at.
  const FieldMm view = viewCenter(CameraParams::fromCalibration(cam.calib), kW, kH);
  for (uint32_t id = 0; id < n; ++id) {
    const FieldRect r = *spec.field.cameraRegion(id, n);
    if (view.x >= r.x_min && view.x <= r.x_max && view.y >= r.y_min && view.y <= r.y_max) cam.calib.camera_id = id;
  }
  spec.cameras.push_back(cam);
  spec.ball.position = {p.aim.x + 400, p.aim.y - 300, 21.5};
  spec.robots = placeRandomRobots(spec, 0, 4, 4, seed);
  const cv::Mat image = Renderer(spec).render(0, 0).image;
  spdlog::debug("true camera at ({:.0f}, {:.0f}, {:.0f}), f {:.1f}, k {:.4f}, pp ({:.1f}, {:.1f})", p.position.x,
                p.position.y, p.position.z, cam.calib.focal_length, cam.calib.distortion, cam.calib.principal_point_x,
                cam.calib.principal_point_y);

  CalibrationRequest req;
  req.camera_id = cam.calib.camera_id;
  req.num_cameras = n;
  PoseResult r;
  r.camera_id = req.camera_id;
  auto t0 = std::chrono::steady_clock::now();
  auto out = calibrateCamera(image, spec.field, req);
  if (out.problem && out.problem->find("--camera-height") != std::string::npos) {
    r.height_asked = true;  // the user answers with the height
    req.camera_height_mm = p.position.z;
    t0 = std::chrono::steady_clock::now();
    out = calibrateCamera(image, spec.field, req);
  }
  // The time of the call that answered (a user who knows the height gives it).
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (out.problem) {
    r.reason = *out.problem;
    return r;
  }
  const FieldRect area = spec.field.withBoundary();
  r.e0 = meanFieldPositionError(cam.calib, out.calibration, 0, area, 48);
  r.e150 = meanFieldPositionError(cam.calib, out.calibration, 150, area, 48);
  const double e = std::max(r.e0, r.e150);
  r.kind = e <= 1.0 ? PoseResult::Within : e <= 3.0 ? PoseResult::Imprecise : PoseResult::Wrong;
  return r;
}

TEST(CalibrationPoseSweep, AutomaticOnVariedViews) {
  const bool full = std::getenv("DV_SCENE_FULL") != nullptr;
  const int per_class = full ? 8 : 2;
  const char* only = std::getenv("DV_SWEEP_ONLY");
  if (only) spdlog::set_level(spdlog::level::debug);
  const View views[] = {View::Centre, View::Halfway, View::Penalty, View::Corner, View::Side, View::Layout};
  std::mt19937 rng(19);
  struct Tally {
    int within = 0, imprecise = 0, wrong = 0, refused = 0;
  };
  std::map<std::string, Tally> tally;
  std::vector<double> times;
  int total = 0, within = 0, wrong = 0;
  std::printf("div view     aim(x,y)      height tilt  yaw     k      pp(du,dv)  mm/px  id  result\n");
  for (int i = 0; i < per_class; ++i)
    for (const View v : views) {
      const bool div_a = (i + int(v)) % 3 != 2;  // two thirds Division A
      const PoseSpec p = drawPose(v, div_a, rng);
      if (only && std::atoi(only) != total) {  // DV_SWEEP_ONLY=i: one pose, for debugging
        ++total;
        continue;
      }
      const PoseResult r = runPose(p, uint64_t(1000 + total));
      ++total;
      times.push_back(r.seconds);
      Tally& t = tally[viewName(v)];
      std::printf("%s   %-8s (%5.0f,%5.0f) %5.0f %5.1f %6.1f %6.3f (%4.0f,%4.0f) %5.2f  %u  ", div_a ? "A" : "B", viewName(v),
                  p.aim.x, p.aim.y, p.position.z, p.tilt_deg, p.yaw_deg, p.k, p.pp_offset.u, p.pp_offset.v,
                  p.mm_per_px, r.camera_id);
      switch (r.kind) {
        case PoseResult::Within: ++t.within, ++within; break;
        case PoseResult::Imprecise: ++t.imprecise; break;
        case PoseResult::Wrong: ++t.wrong, ++wrong; break;
        case PoseResult::Refused: ++t.refused; break;
      }
      if (r.kind == PoseResult::Refused)
        std::printf("refused%s %.1fs: %s\n", r.height_asked ? " (height given)" : "", r.seconds, r.reason.c_str());
      else
        std::printf("%.3f / %.3f mm%s %.1fs\n", r.e0, r.e150, r.height_asked ? " (height given)" : "", r.seconds);
      std::fflush(stdout);
    }
  if (only) return;
  std::sort(times.begin(), times.end());
  std::printf("view      within-1mm  1-3mm  wrong  refused\n");
  for (const auto& [name, t] : tally)
    std::printf("%-9s %6d %8d %6d %8d\n", name.c_str(), t.within, t.imprecise, t.wrong, t.refused);
  std::printf("automatic sweep: %d of %d within 1 mm, %d wrong; time per frame median %.2f s, worst %.2f s\n", within,
              total, wrong, times[times.size() / 2], times.back());
  int imprecise = 0;
  for (const auto& [name, t] : tally) imprecise += t.imprecise;
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(imprecise, 0);
  EXPECT_GE(within, int(std::ceil(0.95 * total)));
}

}  // namespace
}  // namespace dv

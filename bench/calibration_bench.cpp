// Time to calibrate one 2448x2048 frame (rendered by the synth renderer):
// the line observation alone, four-point mode and automatic mode.
#include <benchmark/benchmark.h>

#include "geometry/calibration/calibrate_camera.h"
#include "geometry/calibration/line_pixels.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace {

struct Frame {
  dv::SceneSpec spec;
  cv::Mat image;
  dv::CameraCalibration truth;
};

const Frame& frame() {
  static const Frame f = [] {
    Frame out;
    out.spec.field = dv::FieldModel::divisionB();
    out.spec.cameras.push_back(dv::makeCamera(0, {-2250, 0, 4000}, {-2250, 0, 0}, 1450, -0.08, {0, 0}, 2448, 2048,
                                              {1, 0, 0}));
    out.spec.robots = dv::placeRandomRobots(out.spec, 0, 6, 6, 3);
    dv::Renderer r(out.spec);
    out.image = r.render(0, 0).image;  // Bayer mosaic
    out.truth = out.spec.cameras[0].calib;
    return out;
  }();
  return f;
}

void BM_ObserveLines(benchmark::State& state) {
  const Frame& f = frame();
  const auto region = *f.spec.field.cameraRegion(0, 2);
  for (auto _ : state) benchmark::DoNotOptimize(dv::observeLines(f.image, f.spec.field, region));
}

void BM_CalibrateFourPoint(benchmark::State& state) {
  const Frame& f = frame();
  const auto r = *f.spec.field.cameraRegion(0, 2);
  dv::CalibrationRequest req;
  req.camera_id = 0;
  req.num_cameras = 2;
  req.camera_height_mm = 4000;
  const dv::CameraModel cam(f.truth);
  for (const auto& p : dv::regionCornersCounterClockwise(r.x_min, r.x_max, r.y_min, r.y_max))
    req.points.push_back({p, *cam.fieldToImage(p)});
  for (auto _ : state) benchmark::DoNotOptimize(dv::calibrateCamera(f.image, f.spec.field, req));
}

void BM_CalibrateAutomatic(benchmark::State& state) {
  const Frame& f = frame();
  dv::CalibrationRequest req;
  req.camera_id = 0;
  req.num_cameras = 2;
  req.camera_height_mm = 4000;
  for (auto _ : state) benchmark::DoNotOptimize(dv::calibrateCamera(f.image, f.spec.field, req));
}

BENCHMARK(BM_ObserveLines)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_CalibrateFourPoint)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_CalibrateAutomatic)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();

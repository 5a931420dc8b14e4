// Blob assignment time per frame: 22 robots + ball + 200 clutter blobs, one
// top-down camera over a Division B half field; with and without tracking.
#include <benchmark/benchmark.h>

#include "detection/detector.h"
#include "../tests/detection_test_scene.h"
#include "geometry/field_model.h"

namespace {

dv::BlobList makeFrame(const dv::CameraModel& cam, unsigned seed) {
  dv::test::SceneBuilder s(cam, seed);
  for (const auto& r : s.randomRobots(11, 11, 200, 4300, -2800, 2800)) s.addRobot(r);
  s.addBall({1500, 700});
  s.addClutter(150, 50, 200, 4300, -2800, 2800);
  return s.list;
}

void runDetector(benchmark::State& state, bool tracking) {
  const dv::CameraModel cam(dv::test::topDownCamera());
  dv::DetectorOptions opt;
  opt.tracking = tracking;
  dv::Detector det(cam, dv::FieldModel::divisionB(), opt);
  const dv::BlobList frame = makeFrame(cam, 42);
  dv::Detections out;
  out.robots.reserve(64);
  out.balls.reserve(16);
  double t = 0;
  for (auto _ : state) {
    det.process(frame, t, out);
    t += 1.0 / 72;
    benchmark::DoNotOptimize(out.robots.data());
  }
  state.counters["blobs"] = static_cast<double>(frame.blobs.size());
  state.counters["robots"] = static_cast<double>(out.robots.size());
  state.counters["balls"] = static_cast<double>(out.balls.size());
}

void BM_DetectSingleFrame(benchmark::State& state) { runDetector(state, false); }
void BM_DetectTracking(benchmark::State& state) { runDetector(state, true); }

BENCHMARK(BM_DetectSingleFrame)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DetectTracking)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();

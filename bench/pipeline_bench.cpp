// CPU pixel pipeline on a 2448x2048 Bayer frame of a Div B half field seen
// from above: whole-frame time and each stage (counters, ms per frame).
#include <benchmark/benchmark.h>

#include <memory>

#include "../tests/pipeline_test_scene.h"
#include "pipeline/blob_color_gate.h"
#include "pipeline/cpu_pipeline.h"

namespace dv {
namespace {

struct Fixture {
  std::unique_ptr<CameraModel> camera;
  cv::Mat frame;
};

const Fixture& fixture() {
  static const Fixture f = [] {
    Fixture f;
    // 4 m above the middle of the right half (x in [0, 4800] with boundary).
    f.camera = std::make_unique<CameraModel>(test::topDownCamera(2400, 0, 4000, 1150, 2448, 2048));
    test::PaintedScene s;
    s.supersample = 1;
    s.noise_sigma = 2;
    const auto field = FieldModel::divisionB();
    for (const auto& l : field.lines) s.bands.push_back({l.p1, l.p2, l.thickness});
    const test::Color sides[4] = {test::kPink, test::kGreen, test::kGreen, test::kPink};
    for (int i = 0; i < 11; ++i) {
      addRobot(s, {400.0 + 380 * i, -2500.0 + 470 * i}, 0.3 * i, i % 2 ? test::kBlue : test::kYellow,
               sides);
    }
    s.discs.push_back({{3000, 1200}, 21.5, test::kOrange});
    f.frame = s.render(*f.camera, BayerPattern::RGGB);
    return f;
  }();
  return f;
}

void BM_CpuPipelineBayer2448(benchmark::State& state) {
  const auto& f = fixture();
  PipelineOptions opt;
  opt.threads = static_cast<int>(state.range(0));
  opt.score = state.range(1) ? BlobScoreKind::CircleMin : BlobScoreKind::QuadrantMin;
  CpuPipeline pipe(*f.camera, FieldModel::divisionB(), opt);
  BlobList blobs;
  pipe.process(f.frame, blobs);  // warm-up: first-touch of buffers
  StageTimes sum;
  int64_t n = 0;
  for (auto _ : state) {
    pipe.process(f.frame, blobs);
    const auto& t = pipe.times();
    sum.bayer_ms += t.bayer_ms, sum.color_ms += t.color_ms, sum.rectify_ms += t.rectify_ms;
    sum.gradient_ms += t.gradient_ms, sum.sat_ms += t.sat_ms, sum.score_ms += t.score_ms;
    sum.peaks_ms += t.peaks_ms, sum.total_ms += t.total_ms;
    ++n;
  }
  const double k = n ? 1.0 / n : 0;
  state.counters["bayer_ms"] = sum.bayer_ms * k;
  state.counters["stats_ms"] = sum.color_ms * k;
  state.counters["rectify_color_ms"] = sum.rectify_ms * k;
  state.counters["gradient_ms"] = sum.gradient_ms * k;
  state.counters["sat_ms"] = sum.sat_ms * k;
  state.counters["score_ms"] = sum.score_ms * k;
  state.counters["peaks_ms"] = sum.peaks_ms * k;
  state.counters["total_ms"] = sum.total_ms * k;
  state.counters["blobs"] = static_cast<double>(blobs.blobs.size());
  state.counters["grid_w"] = pipe.grid().width;
  state.counters["grid_h"] = pipe.grid().height;
}
BENCHMARK(BM_CpuPipelineBayer2448)
    ->ArgNames({"threads", "circle"})
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({0, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// What the blob color gate adds per frame (blob_color_gate.h): reading the
// lines' color and the carpet beside them, then the saturation scale from
// a frame's worth of strong peaks (about 120 here). One thread, as the
// pipeline runs it.
void BM_BlobColorGate2448(benchmark::State& state) {
  const auto& f = fixture();
  BlobColorGate gate(*f.camera, FieldModel::divisionB());
  const float rgb[4][3] = {{230, 210, 40}, {40, 80, 200}, {60, 200, 80}, {240, 90, 180}};
  for (auto _ : state) {
    gate.measureNeutral(f.frame, BayerPattern::RGGB);
    gate.beginPeaks();
    for (int i = 0; i < 120; ++i) gate.addPeak(rgb[i % 4]);
    gate.endPeaks();
    benchmark::DoNotOptimize(gate.threshold());
  }
  state.counters["line_points"] = gate.linePoints();
  state.counters["lines_valid"] = gate.neutral().valid;
}
BENCHMARK(BM_BlobColorGate2448)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace dv

BENCHMARK_MAIN();

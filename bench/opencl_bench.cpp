// CPU reference vs OpenCL backend on the same rendered frames (the default
// scene: one top-down camera, 6+6 robots and a ball), at the camera's
// 1224x1024 and at 2448x2048 (the league's Blackfly S). Reports the mean
// frame time per backend plus per-stage times (OpenCL: profiling events) as
// counters. Select the OpenCL device with DV_OPENCL_PLATFORM / DV_OPENCL_DEVICE.
//
//   build-x/opencl_bench --benchmark_min_time=3
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <map>
#include <memory>

#include "pipeline/cpu_pipeline.h"
#include "pipeline/opencl/opencl_pipeline.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace {

struct Frame {
  dv::SceneSpec spec;
  cv::Mat image;
};

// The rendered frame at `scale` x the default scene's image size, made once.
const Frame& frameAt(int scale) {
  static std::map<int, std::unique_ptr<Frame>> cache;
  auto& f = cache[scale];
  if (!f) {
    f = std::make_unique<Frame>();
    f->spec = dv::defaultScene();
    if (scale != 1) dv::scaleImages(f->spec, scale);
    f->spec.antialias = 1;
    dv::Renderer renderer(f->spec);
    f->image = renderer.render(0, 0).image;
  }
  return *f;
}

void stageCounters(benchmark::State& state, const dv::StageTimes& t, double upload_ms) {
  state.counters["upload_ms"] = upload_ms;
  state.counters["bayer_ms"] = t.bayer_ms;
  state.counters["rectify_ms"] = t.rectify_ms + t.color_ms;
  state.counters["gradient_ms"] = t.gradient_ms;
  state.counters["sat_ms"] = t.sat_ms;
  state.counters["score_ms"] = t.score_ms;
  state.counters["peaks_ms"] = t.peaks_ms;
  state.counters["total_ms"] = t.total_ms;
}

void BM_CpuReference(benchmark::State& state) {
  const Frame& f = frameAt(static_cast<int>(state.range(0)));
  const dv::CameraModel cam(f.spec.cameras[0].calib);
  dv::CpuPipeline pipe(cam, f.spec.field, {});
  dv::BlobList blobs;
  for (auto _ : state) {
    if (!pipe.process(f.image, blobs)) state.SkipWithError(pipe.lastError().c_str());
  }
  stageCounters(state, pipe.times(), 0);
  state.counters["blobs"] = static_cast<double>(blobs.blobs.size());
}

void BM_OpenCl(benchmark::State& state) {
  const Frame& f = frameAt(static_cast<int>(state.range(0)));
  const dv::CameraModel cam(f.spec.cameras[0].calib);
  dv::OclDeviceRequest req;
  if (const char* p = std::getenv("DV_OPENCL_PLATFORM")) req.platform = p;
  if (const char* d = std::getenv("DV_OPENCL_DEVICE")) req.device = d;
  std::unique_ptr<dv::OpenClPipeline> pipe;
  try {
    pipe = std::make_unique<dv::OpenClPipeline>(cam, f.spec.field, dv::PipelineOptions{},
                                                dv::selectOpenClDevice(req));
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    for (auto _ : state) {
    }
    return;
  }
  dv::BlobList blobs;
  for (auto _ : state) {
    if (!pipe->process(f.image, blobs)) state.SkipWithError(pipe->lastError().c_str());
  }
  stageCounters(state, pipe->times(), pipe->uploadMs());
  state.counters["blobs"] = static_cast<double>(blobs.blobs.size());
  state.SetLabel(pipe->name());
}

BENCHMARK(BM_CpuReference)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OpenCl)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();

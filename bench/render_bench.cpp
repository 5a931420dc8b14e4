// Rendering speed of the synthetic scene renderer: one full 2448x2048 Bayer
// frame of the top-down preset (11 + 11 robots, a ball) on one core, a
// motion-blurred frame, and the per-scene setup (carpet texture, bins).
// On a shared machine real time includes waiting for a core; the CPU column
// is the one-core cost.
#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>

#include "synth/renderer.h"
#include "synth/scene.h"

namespace {

void BM_RenderTopDownBayer5MP(benchmark::State& state) {
  cv::setNumThreads(int(state.range(0)));
  dv::SceneSpec spec = dv::presetScene("top_down_div_b_half");
  spec.antialias = 2;
  const dv::Renderer renderer(spec);
  for (auto _ : state) {
    dv::RenderedFrame f = renderer.render(0, 0);
    benchmark::DoNotOptimize(f.image.data);
  }
  state.counters["Mpx"] = double(spec.cameras[0].calib.image_width) *
                          spec.cameras[0].calib.image_height / 1e6;
}
BENCHMARK(BM_RenderTopDownBayer5MP)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// A frame of the 60 fps sequence: motion blur (7 time samples where
// something moves) and flicker.
void BM_RenderMotionBlurFrame(benchmark::State& state) {
  cv::setNumThreads(1);
  const dv::SceneSpec spec = dv::presetScene("motion_60fps_flicker");
  const dv::Renderer renderer(spec);
  int frame = 0;
  for (auto _ : state) {
    dv::RenderedFrame f = renderer.render(frame++ % spec.frames, 0);
    benchmark::DoNotOptimize(f.image.data);
  }
}
BENCHMARK(BM_RenderMotionBlurFrame)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RendererSetup(benchmark::State& state) {
  const dv::SceneSpec spec = dv::presetScene("top_down_div_b_half");
  for (auto _ : state) {
    dv::Renderer renderer(spec);
    benchmark::DoNotOptimize(&renderer);
  }
}
BENCHMARK(BM_RendererSetup)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

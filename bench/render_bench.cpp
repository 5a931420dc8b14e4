// Rendering speed of the synthetic scene renderer: one full 2448x2048 Bayer
// frame of the top-down preset (11 + 11 robots, a ball) on one core.
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

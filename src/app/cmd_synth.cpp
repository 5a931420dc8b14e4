// `dotvision synth SCENE.yaml --out DIR`: renders a synthetic scene (frames,
// geometry.json, truth.jsonl). See src/synth/scene.h for the scene format.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "app/commands.h"
#include "core/error.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv::app {

namespace {

struct SynthOptions {
  std::string scene_path;
  std::string preset;
  std::string out_dir;
  int frames = 0;  // 0 = as the scene says
  long long seed = -1;
  double scale = 1;
  bool png = false;
  bool list = false;
};

}  // namespace

CommandFn addSynthCommand(CLI::App& root) {
  auto opt = std::make_shared<SynthOptions>();
  CLI::App* cmd = root.add_subcommand(
      "synth", "Render a synthetic SSL scene: frames (Bayer PGM / PNG), geometry.json, truth.jsonl");
  cmd->add_option("scene", opt->scene_path, "Scene YAML file (see config/scenes/)");
  cmd->add_option("--preset", opt->preset, "Render a shipped preset instead of a file");
  cmd->add_option("--out", opt->out_dir, "Output directory (created if missing)");
  cmd->add_option("--frames", opt->frames, "Render only this many frames")->check(CLI::Range(1, 100000));
  cmd->add_option("--seed", opt->seed, "Override the scene's seed (noise, texture)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--scale", opt->scale, "Scale the images (e.g. 0.25 for quick previews)")
      ->check(CLI::Range(0.01, 4.0));
  cmd->add_flag("--png", opt->png, "Also write PNG RGB frames");
  cmd->add_flag("--list-presets", opt->list, "List the shipped presets and exit");
  return [opt] {
    if (opt->list) {
      for (const std::string& n : presetNames()) std::printf("%s\n", n.c_str());
      return kExitOk;
    }
    if (opt->scene_path.empty() == opt->preset.empty())
      throw InputError("command line", "give either a scene file or --preset NAME");
    if (opt->out_dir.empty()) throw InputError("command line", "--out DIR is required");
    SceneSpec spec = opt->preset.empty() ? loadScene(opt->scene_path) : presetScene(opt->preset);
    if (opt->frames > 0) spec.frames = opt->frames;
    if (opt->seed >= 0) spec.seed = uint64_t(opt->seed);
    if (opt->png) spec.write_png = true;
    if (opt->scale != 1) scaleImages(spec, opt->scale);
    const auto start = std::chrono::steady_clock::now();
    try {
      writeScene(spec, opt->out_dir);
    } catch (const std::invalid_argument& e) {
      throw InputError(opt->preset.empty() ? opt->scene_path : "preset " + opt->preset, e.what());
    }
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("synth: %s: %d frame(s) x %zu camera(s) -> %s (%.1f s)\n", spec.name.c_str(),
                spec.frames, spec.cameras.size(), opt->out_dir.c_str(), s);
    return kExitOk;
  };
}

}  // namespace dv::app

// `dotvision bench`: time per frame of each pipeline stage, the detector and
// the whole, as median and p99 over repeated runs, plus frames per second.
// Without --source it renders the built-in scene at the league's camera
// resolution (2448x2048 Bayer) once and processes those frames repeatedly.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/camera_processor.h"
#include "app/commands.h"
#include "app/synthetic_source.h"
#include "core/error.h"
#include "eval/metrics.h"
#include "geometry/geometry_io.h"
#include "io/frame_source.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv::app {

namespace {

struct BenchArgs {
  std::string source;
  std::string geometry;
  std::optional<uint32_t> camera_id;
  std::string bayer = "rggb";
  std::string bayer_sampling = "auto";
  bool full_search = false;
  int iterations = 100;
  int warmup = 5;
  int max_source_frames = 20;
  int threads = 0;
  int width = 2448;
  int height = 2048;
  std::string backend = "auto";
  std::string opencl_platform;
  std::string opencl_device;
  bool json = false;
};

struct Series {
  const char* name;
  std::vector<double> ms;
};

// The built-in scene with its camera scaled to width x height: the same view
// of the field, so robots stay in the picture.
SceneSpec benchScene(int width, int height) {
  SceneSpec s = defaultScene();
  SceneCamera& cam = s.cameras.at(0);
  const double k = static_cast<double>(width) / cam.calib.image_width;
  CameraCalibration& c = cam.calib;
  c.focal_length *= k;
  c.principal_point_x = (width - 1) / 2.0 + (c.principal_point_x - (c.image_width - 1) / 2.0) * k;
  c.principal_point_y = (height - 1) / 2.0 + (c.principal_point_y - (c.image_height - 1) / 2.0) * k;
  c.image_width = static_cast<uint32_t>(width);
  c.image_height = static_cast<uint32_t>(height);
  s.frames = std::min(s.frames, 3);
  s.antialias = 1;  // rendering is not what is measured
  return s;
}

}  // namespace

CommandFn addBenchCommand(CLI::App& root) {
  auto a = std::make_shared<BenchArgs>();
  CLI::App* cmd = root.add_subcommand(
      "bench",
      "Measure time per frame (per stage, median and p99) and frames per second. Without --source: "
      "the built-in synthetic scene at 2448x2048.");
  cmd->add_option("--source", a->source, "image file, directory, glob or video (as for run)");
  cmd->add_option("--geometry", a->geometry, "SSL_GeometryData as canonical JSON (with --source)");
  cmd->add_option("--camera-id", a->camera_id, "camera id whose calibration is used");
  cmd->add_option("--bayer", a->bayer, "Bayer layout of single-channel images")->default_str("rggb");
  cmd->add_option("--bayer-sampling", a->bayer_sampling, "Bayer mosaic sampling: auto|subsample|full")
      ->default_str("auto");
  cmd->add_flag("--full-search", a->full_search,
                "find blobs on the full grid everywhere (CPU; default: a coarse search on a grid of twice the "
                "spacing where the grid is fine, then the full grid only around its peaks)");
  cmd->add_option("--iterations", a->iterations, "timed frames (default 100)")->check(CLI::PositiveNumber);
  cmd->add_option("--warmup", a->warmup, "untimed frames first (default 5)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-source-frames", a->max_source_frames,
                  "frames loaded from the source and cycled through (default 20)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--threads", a->threads, "pipeline threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--width", a->width, "synthetic image width (default 2448)")->check(CLI::Range(64, 8192));
  cmd->add_option("--height", a->height, "synthetic image height (default 2048)")->check(CLI::Range(64, 8192));
  cmd->add_option("--backend", a->backend, "pixel pipeline backend: auto|cpu|opencl (auto: an OpenCL GPU if there is one, else the CPU reference)")
      ->default_str("auto");
  cmd->add_option("--opencl-platform", a->opencl_platform, "OpenCL platform: index or name substring");
  cmd->add_option("--opencl-device", a->opencl_device, "OpenCL device: index or name substring");
  cmd->add_flag("--json", a->json, "print the result as one JSON object");

  return [a] {
    if (a->width % 2 || a->height % 2) throw InputError("command line", "--width and --height must be even");
    ProcessorOptions options;
    if (!parseBackend(a->backend.c_str(), options.backend.backend))
      throw InputError("command line", "unknown --backend '" + a->backend + "' (expected cpu, opencl or auto)");
    options.backend.opencl_platform = a->opencl_platform;
    options.backend.opencl_device = a->opencl_device;
    options.pipeline.bayer_sampling = bayerSamplingFromName(a->bayer_sampling);
    options.pipeline.coarse_search = !a->full_search;
    // Frames to cycle through, all of one camera.
    std::vector<Frame> frames;
    CameraCalibration calibration;
    FieldModel field;
    std::string what;
    if (!a->source.empty()) {
      if (a->geometry.empty()) throw InputError("command line", "--source needs --geometry");
      const Geometry g = loadGeometry(a->geometry);
      const CameraCalibration* c = nullptr;
      if (a->camera_id) c = g.camera(*a->camera_id);
      else if (g.cameras.size() == 1) c = &g.cameras.front();
      if (!c)
        throw InputError(a->geometry, a->camera_id ? "no calibration for camera id " + std::to_string(*a->camera_id)
                                                   : "holds several calibrations; choose one with --camera-id");
      calibration = *c;
      field = g.field;
      FrameSourceOptions so;
      so.bayer = bayerFormatFromName(a->bayer, "--bayer");
      auto source = openFrameSource(a->source, so);
      Frame f;
      while (static_cast<int>(frames.size()) < a->max_source_frames && source->next(f)) {
        frames.push_back(f);
        f.image = cv::Mat();  // the next frame gets its own buffer
      }
      for (const auto& s : source->skipped())
        std::fprintf(stderr, "dotvision bench: skipped %s: %s\n", s.name.c_str(), s.reason.c_str());
      if (frames.empty()) throw InputError(a->source, "no readable frame");
      what = source->describe();
    } else {
      const SceneSpec spec = benchScene(a->width, a->height);
      const Renderer renderer(spec);
      calibration = spec.cameras[0].calib;
      field = spec.field;
      for (int n = 0; n < spec.frames; ++n) {
        Frame f;
        f.image = renderer.render(n, 0).image;
        f.format = sceneFormat(spec);
        f.index = static_cast<uint32_t>(n);
        f.t_capture = n / spec.fps;
        f.name = "synthetic frame " + std::to_string(n);
        frames.push_back(std::move(f));
      }
      what = "synthetic scene '" + spec.name + "'";
    }
    if (calibration.image_width == 0) {
      calibration.image_width = static_cast<uint32_t>(frames[0].image.cols);
      calibration.image_height = static_cast<uint32_t>(frames[0].image.rows);
    }

    options.pipeline.threads = a->threads;
    options.pipeline.bayer = bayerPatternOf(frames[0].format);
    CameraProcessor processor(calibration, field, options);

    std::vector<Series> series = {{"bayer", {}}, {"rectify", {}}, {"color", {}},  {"gradient", {}},
                                  {"sat", {}},   {"score", {}},   {"peaks", {}},  {"streak", {}}, {"upload", {}}, {"pipeline", {}},
                                  {"detection", {}}, {"total", {}}};
    for (auto& s : series) s.ms.reserve(static_cast<size_t>(a->iterations));
    Detections detections;
    std::string why;
    long blobs = 0, robots = 0, balls = 0;
    double t = 0;
    for (int i = 0; i < a->warmup + a->iterations; ++i) {
      // Advancing time keeps the tracker's motion model in a sane regime.
      Frame& f = frames[static_cast<size_t>(i) % frames.size()];
      f.t_capture = t;
      t += 1.0 / 60;
      if (!processor.process(f, detections, why)) throw InputError(f.name, why);
      if (i < a->warmup) continue;
      const StageTimes& st = processor.pipeline().times();
      const double values[] = {st.bayer_ms, st.rectify_ms, st.color_ms, st.gradient_ms, st.sat_ms,
                               st.score_ms, st.peaks_ms,   st.streak_ms, processor.pipeline().uploadMs(), processor.lastPipelineMs(),
                               processor.lastDetectionMs(),
                               processor.lastPipelineMs() + processor.lastDetectionMs()};
      for (size_t k = 0; k < series.size(); ++k) series[k].ms.push_back(values[k]);
      blobs += static_cast<long>(processor.blobs().blobs.size());
      robots += static_cast<long>(detections.robots.size());
      balls += static_cast<long>(detections.balls.size());
    }
    double total_sum = 0;
    for (double v : series.back().ms) total_sum += v;
    const double mean_total = total_sum / a->iterations;
    const double fps = mean_total > 0 ? 1000.0 / mean_total : 0;
    const unsigned threads = a->threads > 0 ? static_cast<unsigned>(a->threads) : std::thread::hardware_concurrency();

    if (a->json) {
      nlohmann::json j;
      j["source"] = what;
      j["backend"] = processor.pipeline().name();
      j["image_width"] = calibration.image_width;
      j["image_height"] = calibration.image_height;
      j["grid_width"] = processor.pipeline().grid().width;
      j["grid_height"] = processor.pipeline().grid().height;
      j["bayer_sampling"] = processor.pipeline().samplingNote();
      j["iterations"] = a->iterations;
      j["threads"] = threads;
      for (const auto& s : series)
        j["stages_ms"][s.name] = {
            {"min", percentile(s.ms, 0)}, {"median", percentile(s.ms, 0.5)}, {"p99", percentile(s.ms, 0.99)}};
      j["mean_total_ms"] = mean_total;
      j["fps"] = fps;
      j["per_frame"] = {{"blobs", double(blobs) / a->iterations},
                        {"robots", double(robots) / a->iterations},
                        {"balls", double(balls) / a->iterations}};
      std::printf("%s\n", j.dump().c_str());
    } else {
      std::printf("dotvision bench: %s, %ux%u -> grid %dx%d, backend %s, %u threads, %d frames timed\n",
                  what.c_str(), calibration.image_width, calibration.image_height,
                  processor.pipeline().grid().width, processor.pipeline().grid().height,
                  processor.pipeline().name().c_str(),
                  threads, a->iterations);
      std::printf("  %s\n", processor.pipeline().samplingNote().c_str());
      std::printf("  %-10s %10s %10s %10s\n", "stage", "median ms", "p99 ms", "min ms");
      for (const auto& s : series)
        std::printf("  %-10s %10.3f %10.3f %10.3f\n", s.name, percentile(s.ms, 0.5), percentile(s.ms, 0.99),
                    percentile(s.ms, 0));
      std::printf("  mean total %.3f ms per frame = %.1f frames per second\n", mean_total, fps);
      std::printf("  per frame: %.1f blobs, %.1f robots, %.1f balls\n", double(blobs) / a->iterations,
                  double(robots) / a->iterations, double(balls) / a->iterations);
    }
    return kExitOk;
  };
}

}  // namespace dv::app

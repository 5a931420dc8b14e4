// `dotvision eval`: scores detections (JSONL or SSL log) against truth JSONL,
// per camera and overall; `--json` prints one JSON object for machines.
#include <cstdio>
#include <memory>
#include <iterator>
#include <string>
#include <vector>

#include "app/commands.h"
#include "core/error.h"
#include "eval/detection_files.h"
#include "eval/eval_plots.h"
#include "eval/metrics.h"

namespace dv::app {

namespace {

struct EvalArgs {
  std::string truth;
  std::vector<std::string> detections;
  bool json = false;
  std::string plot_dir;
  MatchOptions match;
};

}  // namespace

CommandFn addEvalCommand(CLI::App& root) {
  auto args = std::make_shared<EvalArgs>();
  CLI::App* cmd = root.add_subcommand(
      "eval",
      "Score detections against ground truth: robot recall/precision (same team and id within "
      "60 mm), team-only recall, ID accuracy, ball recall/precision (within 50 mm), position and "
      "orientation errors, false positives per frame; per camera and overall.");
  cmd->add_option("--truth", args->truth,
                  "truth JSONL: one canonical-JSON SSL_DetectionFrame per line")
      ->required();
  cmd->add_option("--detections", args->detections,
                  "detections: JSONL of SSL_WrapperPacket (as `run --jsonl` writes) or SSL log files "
                  "(as `run --record` writes); several files (e.g. one per camera) are merged")
      ->required();
  cmd->add_flag("--json", args->json, "print the report as one JSON object");
  cmd->add_option("--plot", args->plot_dir,
                  "also draw PNGs into this folder: position and orientation error histograms, and a field "
                  "map of missed, misidentified and false robots and balls");
  cmd->add_option("--robot-radius", args->match.robot_radius_mm,
                  "robot match radius in mm (default 60)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--ball-radius", args->match.ball_radius_mm,
                  "ball match radius in mm (default 50)")
      ->check(CLI::PositiveNumber);

  return [args] {
    const DetectionFile truth = readTruthJsonl(args->truth);
    DetectionFile detections;
    for (const std::string& path : args->detections) {
      DetectionFile one = readDetectionFile(path);
      detections.frames.insert(detections.frames.end(), std::make_move_iterator(one.frames.begin()),
                               std::make_move_iterator(one.frames.end()));
      detections.warnings.insert(detections.warnings.end(), one.warnings.begin(), one.warnings.end());
    }
    for (const std::string& w : truth.warnings) std::fprintf(stderr, "dotvision eval: warning: %s\n", w.c_str());
    for (const std::string& w : detections.warnings)
      std::fprintf(stderr, "dotvision eval: warning: %s\n", w.c_str());
    if (truth.frames.empty()) throw InputError(args->truth, "holds no truth frames");
    const EvalReport report = evaluate(truth.frames, detections.frames, args->match);
    if (args->json) {
      std::printf("%s\n", reportJson(report).c_str());
    } else {
      std::printf("%s", formatReport(report).c_str());
    }
    if (!args->plot_dir.empty())
      for (const std::string& f : writeEvalPlots(args->plot_dir, report.overall))
        std::fprintf(args->json ? stderr : stdout, "dotvision eval: wrote %s\n", f.c_str());
    return kExitOk;
  };
}

}  // namespace dv::app

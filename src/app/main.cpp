// dotvision: shape-based shared vision for the RoboCup Small Size League.
#include <opencv2/core/utils/logger.hpp>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <exception>
#include <utility>
#include <vector>

#include "app/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
  using namespace dv::app;
  // OpenCV's own lines (decoder warnings, plugin probing) would come before
  // and between the project's messages; a bad input is reported once, by us.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  CLI::App root{"dotvision: RoboCup SSL shared vision (shape-based blob detection, "
                "automatic calibration, SSL protocol)",
                "dotvision"};
  root.require_subcommand(1);
  std::vector<std::pair<CLI::App*, CommandFn>> commands;
  auto add = [&](CommandFn (*reg)(CLI::App&)) {
    const size_t before = root.get_subcommands({}).size();
    CommandFn fn = reg(root);
    commands.emplace_back(root.get_subcommands({})[before], std::move(fn));
  };
  add(addRunCommand);
  add(addSynthCommand);
  add(addCalibrateCommand);
  add(addEvalCommand);
  add(addBenchCommand);
  add(addGeometryCommand);
  add(addServeCommand);
  add(addCamerasCommand);
  add(addPlotCommand);

  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return root.exit(e);  // --help, --version
    std::fprintf(stderr, "dotvision: command line: %s\n", e.what());
    std::fprintf(stderr, "Run with --help for usage.\n");
    return kExitBadInput;
  }
  for (auto& [sub, fn] : commands) {
    if (!sub->parsed()) continue;
    try {
      return fn();
    } catch (const dv::InputError& e) {
      std::fprintf(stderr, "dotvision %s: %s\n", sub->get_name().c_str(), e.what());
      return kExitBadInput;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "dotvision %s: error: %s\n", sub->get_name().c_str(), e.what());
      return kExitFailure;
    }
  }
  return kExitBadInput;
}

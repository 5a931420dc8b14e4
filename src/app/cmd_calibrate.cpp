// Placeholder until the calibrate subcommand is built: says so and exits non-zero.
#include <cstdio>

#include "app/commands.h"

namespace dv::app {

CommandFn addCalibrateCommand(CLI::App& root) {
  root.add_subcommand("calibrate", "calibrate (not built yet)");
  return [] {
    std::fprintf(stderr, "dotvision calibrate: not built yet\n");
    return kExitUnfinished;
  };
}

}  // namespace dv::app

// Placeholder until the run subcommand is built: says so and exits non-zero.
#include <cstdio>

#include "app/commands.h"

namespace dv::app {

CommandFn addRunCommand(CLI::App& root) {
  root.add_subcommand("run", "run (not built yet)");
  return [] {
    std::fprintf(stderr, "dotvision run: not built yet\n");
    return kExitUnfinished;
  };
}

}  // namespace dv::app

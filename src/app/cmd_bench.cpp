// Placeholder until the bench subcommand is built: says so and exits non-zero.
#include <cstdio>

#include "app/commands.h"

namespace dv::app {

CommandFn addBenchCommand(CLI::App& root) {
  root.add_subcommand("bench", "bench (not built yet)");
  return [] {
    std::fprintf(stderr, "dotvision bench: not built yet\n");
    return kExitUnfinished;
  };
}

}  // namespace dv::app

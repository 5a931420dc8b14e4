// Placeholder until the synth subcommand is built: says so and exits non-zero.
#include <cstdio>

#include "app/commands.h"

namespace dv::app {

CommandFn addSynthCommand(CLI::App& root) {
  root.add_subcommand("synth", "synth (not built yet)");
  return [] {
    std::fprintf(stderr, "dotvision synth: not built yet\n");
    return kExitUnfinished;
  };
}

}  // namespace dv::app

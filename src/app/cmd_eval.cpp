// Placeholder until the eval subcommand is built: says so and exits non-zero.
#include <cstdio>

#include "app/commands.h"

namespace dv::app {

CommandFn addEvalCommand(CLI::App& root) {
  root.add_subcommand("eval", "eval (not built yet)");
  return [] {
    std::fprintf(stderr, "dotvision eval: not built yet\n");
    return kExitUnfinished;
  };
}

}  // namespace dv::app

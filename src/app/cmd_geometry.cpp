// Placeholder until the geometry subcommand is built: says so and exits non-zero.
#include <cstdio>

#include "app/commands.h"

namespace dv::app {

CommandFn addGeometryCommand(CLI::App& root) {
  root.add_subcommand("geometry", "geometry (not built yet)");
  return [] {
    std::fprintf(stderr, "dotvision geometry: not built yet\n");
    return kExitUnfinished;
  };
}

}  // namespace dv::app

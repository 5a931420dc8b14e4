// `dotvision geometry`: the geometry publisher (thesis A.1). Loads the field
// (and any known calibrations), accepts processors' calibrations on a UDP
// port and publishes SSL_GeometryData on the league's vision group, until
// --duration / --count or Ctrl-C.
#include <spdlog/spdlog.h>

#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "core/error.h"
#include "geometry/geometry_io.h"
#include "net/geometry_publisher.h"

namespace dv::app {

namespace {

struct GeometryArgs {
  std::string field;
  GeometryPublisherOptions publisher;
  double duration_s = 0;
  uint64_t count = 0;
};

// The running publisher, for the signal handler (stop() is an atomic store).
GeometryPublisher* g_running = nullptr;

extern "C" void stopOnSignal(int) {
  if (g_running) g_running->stop();
}

}  // namespace

CommandFn addGeometryCommand(CLI::App& root) {
  auto a = std::make_shared<GeometryArgs>();
  CLI::App* cmd = root.add_subcommand(
      "geometry",
      "Geometry publisher: the single source of truth for the field. Merges the calibrations "
      "processors send and publishes SSL_GeometryData on the vision group every --interval s.");
  cmd->add_option("--field", a->field,
                  "field file: SSL_GeometryData as canonical JSON (.json) or YAML (.yaml); "
                  "calibrations in it are published from the start (e.g. config/fields/division_a.json)")
      ->required();
  cmd->add_option("--listen-port", a->publisher.listen_port, "UDP port for processors' calibrations")
      ->default_str(std::to_string(kGeometryListenPort));
  cmd->add_option("--listen-addr", a->publisher.listen_addr, "local IPv4 address to listen on")
      ->default_str("0.0.0.0");
  cmd->add_option("--allow", a->publisher.allowed_sources,
                  "IPv4 address a calibration may come from (repeatable); others are dropped")
      ->default_str("127.0.0.1");
  cmd->add_option("--num-cameras", a->publisher.num_cameras, "accept camera ids 0 .. N-1")
      ->default_str("8")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--interval", a->publisher.interval_s, "seconds between publications")
      ->default_str("3.0")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--multicast-group", a->publisher.group, "vision multicast group")->default_str("224.5.23.2");
  cmd->add_option("--multicast-port", a->publisher.port, "vision multicast port")->default_str("10006");
  cmd->add_option("--multicast-interface", a->publisher.interface_addr,
                  "local IPv4 address of the interface to publish on (default: by route)");
  cmd->add_option("--duration", a->duration_s, "stop after this many seconds (default: run until Ctrl-C)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--count", a->count, "stop after this many publications")->check(CLI::PositiveNumber);

  return [a] {
    Geometry geometry = loadGeometry(a->field);
    GeometryPublisher publisher(std::move(geometry), a->publisher);
    g_running = &publisher;
    auto previous_int = std::signal(SIGINT, stopOnSignal);
    auto previous_term = std::signal(SIGTERM, stopOnSignal);
    publisher.run(a->duration_s, a->count);
    std::signal(SIGINT, previous_int);
    std::signal(SIGTERM, previous_term);
    g_running = nullptr;
    const auto& s = publisher.stats();
    std::printf(
        "geometry: published %llu packet(s) with %zu camera(s); %llu calibration(s) accepted, "
        "%llu rejected; dropped %llu malformed and %llu from unknown sources; %llu send error(s)\n",
        (unsigned long long)s.published, publisher.geometry().cameras.size(),
        (unsigned long long)s.accepted, (unsigned long long)s.rejected, (unsigned long long)s.malformed,
        (unsigned long long)s.unknown_source, (unsigned long long)s.send_errors);
    return s.published > 0 ? kExitOk : kExitFailure;
  };
}

}  // namespace dv::app

// `dotvision serve SITE.yaml`: every camera of a site config in one process,
// each with its own threads, publishing on the vision group; the game
// controller's team names set the robot heights; SIGHUP reloads the file
// (a bad file is refused and the running config stays); a status table
// every few seconds and, with --status-file, the status records as JSON
// once a second. Ctrl-C / SIGTERM stop cleanly with a summary.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "app/commands.h"
#include "app/console_server.h"
#include "app/log_ring.h"
#include "app/serve_status.h"
#include "app/signals.h"
#include "app/site_config.h"
#include "app/site_runtime.h"
#include "core/error.h"
#include "eval/metrics.h"
#include "net/referee_listener.h"

namespace dv::app {

namespace {

struct ServeArgs {
  std::string config;
  bool check = false;
  bool quiet = false;
  std::string status_file;
  std::string record_raw;
  std::string http;  // --http; only when given (else the config's console.http)
  bool http_given = false;
  double duration = 0;
};

void logLine(const std::string& line) {
  const std::time_t t = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%H:%M:%S", std::localtime(&t));
  std::fprintf(stderr, "%s dotvision serve: %s\n", stamp, line.c_str());
}

// Written to a temporary name and renamed, so a reader never sees half a file.
void writeStatusFile(const std::string& path, const nlohmann::json& j) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << j.dump(1) << '\n';
    if (!out) return;
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
}

int serve(const ServeArgs& a) {
  installSignalHandlers();  // first: every thread started later inherits the blocked signals
  SiteConfig config = loadSiteConfig(a.config);
  if (!a.record_raw.empty()) config.record.raw_dir = a.record_raw;
  std::printf("%s", describeSiteConfig(config).c_str());
  if (a.check) {
    std::printf("%s: valid\n", a.config.c_str());
    return kExitOk;
  }
  std::fflush(stdout);
  // Every line also kept in memory for the console's Status page.
  auto ring = std::make_shared<LogRing>();
  const auto log = [ring](const std::string& line) {
    logLine(line);
    ring->add(line);
  };
  SiteRuntime runtime(config, log);

  std::unique_ptr<RefereeListener> referee;
  if (config.network.referee) {
    RefereeListenerOptions ro;
    ro.group = config.network.referee_group;
    ro.port = config.network.referee_port;
    ro.interface_addr = config.network.interface_addr;
    try {
      referee = std::make_unique<RefereeListener>(ro);
    } catch (const InputError& e) {
      log(std::string("not listening to the game controller: ") + e.what());
    }
  }
  // The console hooks into the cameras before they start.
  std::unique_ptr<ConsoleServer> console = makeConsole(runtime, a.http_given ? &a.http : nullptr, log, ring);
  runtime.start();
  if (console) {
    console->start();
    if (runtime.config().console.token_file.empty())
      // Terminal only: the log kept for the console is readable without the token.
      logLine("console: " + console->url() + "#token=" + console->token() + " (changes need the token " +
              console->token() + ")");
    else
      log("console: " + console->url() + " (changes need the token in " + runtime.config().console.token_file + ")");
  }
  log("running " + std::to_string(runtime.cameraCount()) + " camera(s); SIGHUP reloads " + a.config);

  using Clock = std::chrono::steady_clock;
  const auto started = Clock::now();
  auto next_second = started + std::chrono::seconds(1);
  auto next_table = started + std::chrono::duration<double>(config.status_interval);
  uint64_t referee_seen = 0;
  RefereeSnapshot teams;
  std::vector<CameraStatus> last;
  while (!stopRequested()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    runtime.tick();
    if (referee && referee->changeCount() != referee_seen) {
      teams = referee->snapshot();
      referee_seen = teams.changes;
      log("game controller: yellow '" + teams.yellow_name + "', blue '" + teams.blue_name + "'");
      runtime.setReferee(teams);
    }
    if (takeDumpRequest() && !runtime.dumpRaw("SIGUSR1"))
      log("no raw frames to write (set record.raw_dir or --record-raw) or a dump is still being written");
    if (console) console->service(runtime);
    if (takeReloadRequest()) {
      try {
        SiteConfig next = loadSiteConfig(a.config);
        if (!a.record_raw.empty()) next.record.raw_dir = a.record_raw;
        for (const std::string& note : runtime.reload(next)) log("reload: " + note);
      } catch (const InputError& e) {
        log(std::string("reload refused, the running config stays: ") + e.what());
      }
    }
    const auto now = Clock::now();
    if (now >= next_second) {
      next_second += std::chrono::seconds(1);
      last = runtime.status();
      if (!a.status_file.empty() || console) {
        const nlohmann::json status = serveStatusJson(last, runtime.config().path, teams);
        if (!a.status_file.empty()) writeStatusFile(a.status_file, status);
        if (console) console->setStatus(status);
      }
      const double interval = runtime.config().status_interval;
      if (!a.quiet && interval > 0 && now >= next_table) {
        std::fprintf(stderr, "%s", statusTable(last).c_str());
        next_table = now + std::chrono::duration<double>(interval);
      }
    }
    if (a.duration > 0 && now - started >= std::chrono::duration<double>(a.duration)) break;
  }
  if (console) console->stop();
  referee.reset();
  runtime.stop();
  runtime.finish();
  std::printf("dotvision serve: %s, %.1f s%s\n", a.config.c_str(),
              std::chrono::duration<double>(Clock::now() - started).count(),
              stopRequested() ? " (stopped by a signal)" : "");
  for (size_t i = 0; i < runtime.cameraCount(); ++i) {
    CameraRunner& r = runtime.runner(i);
    const CameraStatus s = r.status();
    const CameraRunner::Times t = r.times();
    std::printf("  camera %u: %llu received, %llu processed, %llu dropped, %llu skipped; latency p50 %.2f ms, "
                "p99 %.2f ms; %s\n",
                s.camera_id, static_cast<unsigned long long>(s.counters.frames_in),
                static_cast<unsigned long long>(s.counters.processed),
                static_cast<unsigned long long>(s.counters.dropped),
                static_cast<unsigned long long>(s.counters.skipped),
                t.total_ms.empty() ? -1.0 : percentile(t.total_ms, 0.5),
                t.total_ms.empty() ? -1.0 : percentile(t.total_ms, 0.99), s.source.c_str());
  }
  std::printf("  output: %s\n", runtime.outputsSummary().c_str());
  return kExitOk;
}

}  // namespace

CommandFn addServeCommand(CLI::App& root) {
  auto a = std::make_shared<ServeArgs>();
  CLI::App* cmd = root.add_subcommand(
      "serve", "Run every camera of a site config (YAML) live and publish their detections; SIGHUP reloads it. "
               "Example: config/site.example.yaml (synthetic cameras, runs anywhere).");
  cmd->add_option("config", a->config, "site config file")->required();
  cmd->add_flag("--check", a->check, "validate the config and exit");
  cmd->add_flag("--quiet", a->quiet, "no status table on the terminal");
  cmd->add_option("--status-file", a->status_file, "write every camera's status record here as JSON each second");
  cmd->add_option("--record-raw", a->record_raw,
                  "keep the last seconds of raw frames (record.raw_seconds) and write them here on SIGUSR1 "
                  "or a change of health (overrides record.raw_dir)");
  cmd->add_option("--http", a->http,
                  "the console in the browser listens here, IPv4ADDR:PORT (default: the config's console.http, "
                  "127.0.0.1:8080; \"\": no console)")
      ->each([a](const std::string&) { a->http_given = true; });
  cmd->add_option("--duration", a->duration, "stop after this many seconds (default: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  return [a] { return serve(*a); };
}

}  // namespace dv::app

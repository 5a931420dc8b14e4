#pragma once
// `dotvision serve` with its console, as the console tests run it: two
// synthetic 1224x1024 cameras over a Division B field (both teams in
// camera 0's view), publishing on loopback multicast at a port of this
// process's own, the console on 127.0.0.1 at a free port (--http
// 127.0.0.1:0; the port and the printed token are read from its log), or
// `dotvision run --http` on camera 0 alone.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "temp_dir.h"

namespace dv {

class ConsoleServe {
 public:
  // Robots placed in camera 0's view: 4 yellow and 4 blue (camera 1's may stand in the overlap).
  static constexpr int kCamera0Robots = 8;
  static constexpr int kWidth = 1224, kHeight = 1024;

  // `config_tail`: more YAML at the end of the site config.
  explicit ConsoleServe(const std::string& prefix, const std::string& config_tail = "") : dir_(prefix) {
    std::ofstream(dir_.file("scene.yaml")) << R"(name: console_test
seed: 3
field: division_b
cameras:
  - {id: 0, position: [-2250, 0, 5000], look_at: [-2250, 0, 0], up: [-1, 0, 0], focal_length: 875, distortion: 0.03, size: [1224, 1024]}
  - {id: 1, position: [2250, 0, 5000], look_at: [2250, 0, 0], up: [-1, 0, 0], focal_length: 875, distortion: 0.03, size: [1224, 1024]}
random_robots:
  - {yellow: 4, blue: 4, camera: 0, margin_px: 80}
  - {yellow: 2, blue: 3, camera: 1, margin_px: 80}
ball: {position: [-1800, 400]}
frames: 1
)";
    const int vision_port = 45000 + ::getpid() % 1000;
    config_ = dir_.file("site.yaml");
    std::ofstream(config_) << "cameras:\n"
                           << "  - {id: 0, source: synthetic://" << dir_.file("scene.yaml") << "/0, threads: 1, backend: cpu}\n"
                           << "  - {id: 1, source: synthetic://" << dir_.file("scene.yaml") << "/1, threads: 1, backend: cpu}\n"
                           << "network:\n  vision: {group: 224.5.23.2, port: " << vision_port
                           << ", interface: 127.0.0.1}\n  referee: {enabled: false}\n"
                           << "robot_heights:\n  default: 140   # the league's usual\n"
                           << config_tail << "status_interval: 0\n";
  }
  ~ConsoleServe() { stop(); }

  // Starts serve and waits (up to 60 s) for the console's line in its log.
  bool start() { return startWith({"serve", config_, "--http", "127.0.0.1:0"}); }
  // The same console from `dotvision run` on camera 0 of the scene alone.
  bool startRun() {
    return startWith({"run", "--source", "synthetic://" + dir_.file("scene.yaml") + "/0", "--no-publish", "--quiet",
                      "--backend", "cpu", "--threads", "1", "--http", "127.0.0.1:0"});
  }
  bool startWith(const std::vector<std::string>& args) {
    pid_ = ::fork();
    if (pid_ == 0) {
      if (!freopen(dir_.file("serve.log").c_str(), "w", stdout)) _exit(126);
      ::dup2(STDOUT_FILENO, STDERR_FILENO);
      std::vector<char*> argv = {const_cast<char*>(DV_CLI_PATH)};
      for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      execv(DV_CLI_PATH, argv.data());
      _exit(127);
    }
    const std::regex line(R"(console: http://127\.0\.0\.1:(\d+)/(#token=([0-9a-f]+))?)");
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < until) {
      std::smatch m;
      const std::string text = log();
      if (std::regex_search(text, m, line)) {
        port_ = std::stoi(m[1]);
        printed_token_ = m[3];
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
  }
  void stop() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
  }

  std::string log() const { return read(dir_.file("serve.log")); }
  std::string configText() const { return read(config_); }
  const std::string& configPath() const { return config_; }
  int port() const { return port_; }
  pid_t pid() const { return pid_; }
  const std::string& printedToken() const { return printed_token_; }
  std::string url(const std::string& path) const { return "http://127.0.0.1:" + std::to_string(port_) + path; }
  const TempDir& dir() const { return dir_; }

  // Polls `ok` every 200 ms until it holds or timeout_s passed.
  static bool waitFor(const std::function<bool()>& ok, double timeout_s = 60) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < until) {
      if (ok()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    return ok();
  }

 private:
  static std::string read(const std::string& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  TempDir dir_;
  std::string config_;
  pid_t pid_ = -1;
  int port_ = 0;
  std::string printed_token_;
};

}  // namespace dv

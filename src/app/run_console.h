#pragma once
// `dotvision run --http ADDR:PORT`: the console of serve (console_server.h)
// over run's single live camera. Everything but the config works as under
// serve; run has no config file (its settings are its command line), so the
// Settings page shows none and changes to it are refused.
#include <memory>
#include <string>

#include "app/console_host.h"
#include "app/console_server.h"
#include "live/camera_status.h"

namespace dv::app {

class RunConsole : public ConsoleHost {
 public:
  // Hooks into `runner` (before it starts) and listens on `http`; throws
  // InputError for a malformed address. A console that cannot listen is
  // logged and left out (ok() false).
  RunConsole(CameraRunner& runner, const Geometry& geometry, PacketOutputs& outputs, const std::string& http,
             ConsoleServer::LogFn log);
  ~RunConsole() override;
  bool ok() const { return server_ != nullptr; }
  void start();  // after the runner started: serves and prints where
  // run's main loop: each turn (the console's requests), and once a second.
  void service();
  void setStatus(const CameraStatus& status);

  const SiteConfig& config() const override { return config_; }
  const Geometry& geometry() const override { return geometry_; }
  size_t cameraCount() const override { return 1; }
  CameraRunner& runner(size_t) override { return runner_; }
  std::vector<std::string> reload(const SiteConfig& next) override;
  std::vector<std::string> setCalibration(const CameraCalibration& c, const std::string& publisher) override;

 private:
  CameraRunner& runner_;
  Geometry geometry_;
  PacketOutputs& outputs_;
  SiteConfig config_;  // path "": none
  ConsoleServer::LogFn log_;
  std::unique_ptr<ConsoleServer> server_;
};

}  // namespace dv::app

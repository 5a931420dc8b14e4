#pragma once
// What the console's HTTP threads share with the host's main loop (serve's
// or run's, console_host.h). The main loop owns the host, which is not
// thread-safe: it publishes the
// status document once a second here, and a config change asked for on the
// console is queued here and applied by the main loop (service()) exactly
// as a SIGHUP reload; the HTTP thread waits for the notes. Camera images
// and detections come through each camera's CameraFeed.
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/camera_feed.h"
#include "app/console_calibration.h"
#include "app/console_layers.h"
#include "app/log_ring.h"
#include "app/site_config.h"
#include "geometry/geometry_io.h"

namespace dv::app {

class ConsoleHost;

class ConsoleState {
 public:
  // `config_text`: the file's text as it was loaded; `config`: its parse.
  ConsoleState(const Geometry& geometry, const std::vector<uint32_t>& camera_ids, const SiteConfig& config,
               std::string config_text);

  // Main loop: once a second.
  void setStatus(nlohmann::json status);
  // Main loop: each turn; applies the queued config changes.
  void service(ConsoleHost& host);

  // HTTP threads.
  nlohmann::json status() const;
  // A copy: an accepted calibration replaces the camera's in it.
  Geometry geometry() const;
  void setCameraCalibration(const CameraCalibration& c);
  CameraFeed* feed(uint32_t camera_id);
  std::shared_ptr<CameraFeed> sharedFeed(uint32_t camera_id);
  const std::vector<std::shared_ptr<CameraFeed>>& feeds() const { return feeds_; }
  std::string configText() const;
  SiteConfig config() const;
  const std::string& configPath() const { return config_path_; }
  CalibrationRuns& calibrations() { return calibrations_; }
  LayerPipelines& layers() { return layers_; }
  // serve's recent log lines (null: none kept).
  void setLogRing(std::shared_ptr<const LogRing> ring) { log_ring_ = std::move(ring); }
  const LogRing* logRing() const { return log_ring_.get(); }
  struct ReloadResult {
    bool applied = false;  // false: the main loop did not take it in time
    std::vector<std::string> notes;
  };
  // Hands a validated config (and the text it came from) to the main loop
  // and waits up to timeout_s for what reload() said.
  ReloadResult reload(const SiteConfig& next, const std::string& text, double timeout_s);
  // Runs `task` on the main loop (the runtime is its alone) and waits up to
  // timeout_s for its notes; an InputError it throws comes back as the
  // single note with applied true and `error` set.
  using Task = std::function<std::vector<std::string>(ConsoleHost&)>;
  struct TaskResult : ReloadResult {
    std::string error;
  };
  TaskResult onMainLoop(Task task, double timeout_s);

 private:
  struct Job {
    Task task;
    std::promise<std::vector<std::string>> notes;
  };
  Geometry geometry_;
  const std::string config_path_;
  std::vector<std::shared_ptr<CameraFeed>> feeds_;  // shared with the cameras' frame hooks
  mutable std::mutex mutex_;
  nlohmann::json status_;
  SiteConfig config_;  // the running config as the console last set it or as loaded
  std::string config_text_;
  std::deque<std::shared_ptr<Job>> jobs_;
  std::shared_ptr<const LogRing> log_ring_;
  LayerPipelines layers_;
  CalibrationRuns calibrations_;  // last: its workers may still touch the members above
};

}  // namespace dv::app

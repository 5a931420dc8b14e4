#pragma once
// What `serve` runs for a site config: a CameraRunner per camera (a camera
// whose source or processor fails is reported and left out; the others
// run), the shared outputs, the geometry (from the cameras' scenes, a file,
// the in-process geometry publisher or the network), and the robot heights
// from the config's team table and the game controller's team names.
// reload() takes a new, validated config: detector options, robot heights,
// camera settings, network targets and the geometry file's calibrations
// change in place, tracks stay;
// changes that need a restart (cameras added, removed or moved to another
// source) are named and not applied.
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <thread>
#include <string>
#include <vector>

#include "app/camera_runner.h"
#include "app/console_host.h"
#include "app/packet_outputs.h"
#include "app/site_config.h"
#include "geometry/geometry_io.h"
#include "live/camera_status.h"
#include "live/raw_ring.h"
#include "net/referee_listener.h"
#include "net/team_heights.h"

namespace dv {
class GeometryPublisher;
}

namespace dv::app {

class SiteRuntime : public ConsoleHost {
 public:
  using LogFn = std::function<void(const std::string&)>;
  // Throws InputError when no camera can run or the geometry cannot be had.
  SiteRuntime(const SiteConfig& config, LogFn log);
  ~SiteRuntime() override;

  void start();
  void stop();
  // Once a second from the main loop: status records (health changes are logged).
  std::vector<CameraStatus> status();
  // A validated new config; returns what was applied and what was not.
  std::vector<std::string> reload(const SiteConfig& next) override;
  // The game controller's teams changed: new heights from the next frame
  // (unknown team names are logged once each).
  void setReferee(const RefereeSnapshot& referee);
  // From the main loop, often: the geometry repeats when due, and the
  // calibrations accepted here are sent again to an external geometry
  // publisher every few seconds, so a publisher that restarts from its file
  // learns them back while the processors never stop using them.
  void tick();
  // A new calibration for camera c.camera_id (accepted on the console): its
  // processor is rebuilt with it at the next frame and the published
  // geometry changes. With an external geometry publisher (network.geometry
  // "publisher") it is sent there, to `publisher` (ADDR or ADDR:PORT; ""
  // 127.0.0.1:10013). Returns what was done; throws InputError when no
  // camera of that id runs or the publisher address is bad.
  std::vector<std::string> setCalibration(const CameraCalibration& c, const std::string& publisher) override;
  // Writes the raw rings (record.raw_dir) to a new folder, off the main
  // loop's thread; `why` goes into the log line. False when no ring is kept
  // or a dump is still being written.
  bool dumpRaw(const std::string& why);
  const SiteConfig& config() const override { return config_; }
  const Geometry& geometry() const override { return geometry_; }
  size_t cameraCount() const override { return runners_.size(); }
  CameraRunner& runner(size_t i) override { return *runners_[i]; }
  std::string outputsSummary() const { return outputs_->describe(); }
  void finish() { outputs_->finish(); }

 private:
  DetectorOptions detectorOptions() const;
  void rebuildHeights();  // heights_ from config_.robot_heights, then resolved for referee_
  ProcessorOptions processorOptions(const SiteCamera& cam) const;
  void reloadGeometry(const SiteConfig& next, std::vector<std::string>& notes);

  SiteConfig config_;
  LogFn log_;
  Geometry geometry_;
  TeamHeights heights_;
  RefereeSnapshot referee_;
  TeamHeightsResult current_heights_;
  std::unique_ptr<PacketOutputs> outputs_;
  std::unique_ptr<GeometryPublisher> geometry_publisher_;
  std::thread geometry_thread_;
  std::vector<std::unique_ptr<CameraRunner>> runners_;
  std::vector<size_t> config_index_;  // runner i serves config_.cameras[config_index_[i]]
  std::vector<std::shared_ptr<RawRing>> rings_;  // per runner, when raw frames are kept
  std::thread dump_thread_;
  // Calibrations accepted on the console and sent to an external publisher.
  struct SentCalibrations {
    std::string addr;
    uint16_t port = 0;
    std::vector<CameraCalibration> cameras;
    std::chrono::steady_clock::time_point next;
  };
  std::mutex sent_mutex_;
  SentCalibrations sent_;
  std::atomic<bool> dumping_{false};
};

}  // namespace dv::app

// The geometry publisher restarts (a crash, an operator's restart) while
// serve runs with `geometry: {source: publisher}`: the cameras go on with
// their calibrations, and a calibration accepted on this processor's
// console reaches the new publisher again without anyone doing anything.
// Real UDP on loopback: the publisher's listen port and the vision group.
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>
#include <thread>

#include "app/site_config.h"
#include "app/site_runtime.h"
#include "app/synthetic_camera.h"
#include "net/geometry_publisher.h"
#include "net/multicast.h"

namespace dv::app {
namespace {

const char* kSource = "synthetic://two_cameras_overlap/0";

// A geometry publisher stepping in a thread of its own, as `dotvision geometry` does.
class RunningPublisher {
 public:
  RunningPublisher(const Geometry& g, uint16_t listen_port, uint16_t vision_port) {
    GeometryPublisherOptions o;
    o.listen_addr = "127.0.0.1";
    o.listen_port = listen_port;
    o.port = vision_port;
    o.interface_addr = "127.0.0.1";
    o.interval_s = 0.5;
    publisher_ = std::make_unique<GeometryPublisher>(g, o);
    publisher_->start();
    thread_ = std::thread([this] {
      while (publisher_->step(0.05)) {
      }
    });
  }
  ~RunningPublisher() {
    publisher_->stop();
    thread_.join();
  }
  uint16_t listenPort() const { return publisher_->listenPort(); }

 private:
  std::unique_ptr<GeometryPublisher> publisher_;
  std::thread thread_;
};

// Receives on the vision group until `accept` holds for a packet, calling
// tick() in between as serve's main loop does. False after `seconds`.
template <class Accept>
bool receiveUntil(MulticastReceiver& rx, SiteRuntime& runtime, double seconds, Accept accept) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  std::string payload;
  ssl::SSL_WrapperPacket p;
  while (std::chrono::steady_clock::now() < until) {
    runtime.tick();
    if (rx.receive(0.05, payload) && p.ParseFromString(payload) && accept(p)) return true;
  }
  return false;
}

bool publishesCamera0At(const ssl::SSL_WrapperPacket& p, double tx) {
  if (!p.has_geometry()) return false;
  for (const auto& c : p.geometry().calib())
    if (c.camera_id() == 0) return std::abs(c.tx() - tx) < 0.01;
  return false;
}

TEST(SitePublisherRestart, CamerasKeepTheirCalibrationAndTheNewPublisherLearnsItBack) {
  const Geometry scene = SyntheticCamera(kSource).geometry();
  Geometry initial;
  initial.field = scene.field;
  initial.cameras.push_back(*scene.camera(0));
  const uint16_t vision_port = static_cast<uint16_t>(21000 + ::getpid() % 20000);
  MulticastReceiver rx("224.5.23.2", vision_port, "127.0.0.1");
  auto publisher = std::make_unique<RunningPublisher>(initial, 0, vision_port);
  const uint16_t listen_port = publisher->listenPort();

  std::ostringstream yaml;
  yaml << "cameras:\n  - {id: 0, source: \"" << kSource << "\", threads: 1, backend: cpu}\n"
       << "network:\n  vision: {group: 224.5.23.2, port: " << vision_port << ", interface: 127.0.0.1}\n"
       << "  geometry: {source: publisher, timeout: 20}\n"
       << "  referee: {enabled: false}\n"
       << "status_interval: 0\n";
  std::vector<std::string> log;
  SiteRuntime runtime(parseSiteConfig(yaml.str(), "site.yaml"), [&](const std::string& l) { log.push_back(l); });
  ASSERT_NE(runtime.geometry().camera(0), nullptr);
  runtime.start();

  // The operator accepts a corrected calibration: 5 mm along the camera's x.
  CameraCalibration corrected = *initial.camera(0);
  corrected.tx += 5;
  const auto notes = runtime.setCalibration(corrected, "127.0.0.1:" + std::to_string(listen_port));
  ASSERT_FALSE(notes.empty());
  EXPECT_NE(notes.back().find("sent to the geometry publisher"), std::string::npos) << notes.back();
  EXPECT_TRUE(receiveUntil(rx, runtime, 10, [&](const auto& p) { return publishesCamera0At(p, corrected.tx); }));

  // The publisher goes away; detection goes on with the corrected calibration.
  publisher.reset();
  EXPECT_TRUE(receiveUntil(rx, runtime, 10, [](const auto& p) { return p.has_detection(); }));
  EXPECT_DOUBLE_EQ(runtime.geometry().camera(0)->tx, corrected.tx);

  // It comes back from its file, without the correction, and learns it back.
  publisher = std::make_unique<RunningPublisher>(initial, listen_port, vision_port);
  EXPECT_TRUE(receiveUntil(rx, runtime, 10, [&](const auto& p) { return publishesCamera0At(p, initial.camera(0)->tx); }))
      << "the restarted publisher's own geometry first";
  EXPECT_TRUE(receiveUntil(rx, runtime, 15, [&](const auto& p) { return publishesCamera0At(p, corrected.tx); }))
      << "then the calibration this processor uses";
  EXPECT_DOUBLE_EQ(runtime.geometry().camera(0)->tx, corrected.tx);
  runtime.stop();
}

}  // namespace
}  // namespace dv::app

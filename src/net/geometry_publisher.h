#pragma once
// The geometry publisher (thesis A.1): the single source of truth for the
// field. Processors send it their camera calibrations; it merges them and
// periodically publishes one SSL_GeometryData with the field and every
// camera's calibration on the league's vision group, as SSL-Vision does.
//
// Wire contract
//  - Processor -> publisher: unicast UDP to the publisher's --listen-port
//    (default 10013), one SSL_WrapperPacket per datagram whose `geometry`
//    carries the processor's calibration(s) in `calib`. Its `field` is
//    required by the schema but ignored: the publisher's field wins.
//  - Publisher -> everyone: SSL_WrapperPacket with only `geometry` and
//    `source` on 224.5.23.2:10006, every interval (SSL-Vision: 3 s) and at
//    once when a calibration changes. The source is kGeometryPacketSource,
//    SSL_SOURCE_SSL_VISION, the same as dotvision's detection packets: it
//    stands in for the league's vision system, and consumers that filter on
//    the source expect that value.
//  - Datagrams from addresses not in `allowed_sources`, that do not parse,
//    or whose calibrations are implausible or have ids outside
//    0..num_cameras-1 are dropped, counted, and logged at most once per
//    log_interval_s per kind (with the number dropped in between).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dotvision/ssl_wrapper.pb.h"
#include "geometry/geometry_io.h"

namespace dv {

inline constexpr uint16_t kGeometryListenPort = 10013;
inline constexpr dv::ssl::SSL_Source kGeometryPacketSource = dv::ssl::SSL_SOURCE_SSL_VISION;

struct GeometryPublisherOptions {
  std::string listen_addr = "0.0.0.0";  // local IPv4 address for processors' packets
  uint16_t listen_port = kGeometryListenPort;  // 0 = any free port (tests)
  std::vector<std::string> allowed_sources = {"127.0.0.1"};  // IPv4 senders accepted
  uint32_t num_cameras = 8;  // accepted camera ids: 0 .. num_cameras-1
  double interval_s = 3.0;   // periodic publication
  std::string group = "224.5.23.2";
  uint16_t port = 10006;
  std::string interface_addr;  // local address to publish on ("" = by route)
  double log_interval_s = 5.0;  // at most one drop message per kind per interval
};

struct GeometryPublisherStats {
  uint64_t datagrams = 0;       // received on the listen port
  uint64_t unknown_source = 0;  // dropped: sender not allowed
  uint64_t malformed = 0;       // dropped: not an SSL_WrapperPacket with geometry
  uint64_t rejected = 0;        // calibrations dropped: implausible or id out of range
  uint64_t accepted = 0;        // calibrations merged (including unchanged repeats)
  uint64_t published = 0;       // geometry packets sent
  uint64_t send_errors = 0;
};

class MulticastSender;
class UdpSocket;
class RateLimitedLog;

class GeometryPublisher {
 public:
  enum class Verdict { Accepted, UnknownSource, Malformed, Rejected };

  // `initial`: the field and any calibrations known in advance (validated by
  // loadGeometry; ids must be below num_cameras). Opens both sockets; throws
  // InputError on bad options or when a socket cannot be set up.
  GeometryPublisher(Geometry initial, GeometryPublisherOptions options);
  ~GeometryPublisher();
  GeometryPublisher(const GeometryPublisher&) = delete;
  GeometryPublisher& operator=(const GeometryPublisher&) = delete;

  // Publishes once and schedules the next periodic publication.
  void start();
  // Waits at most max_wait_s for processors' packets, handles those that
  // arrived (at most a bounded batch), and publishes when due or when a
  // calibration changed. Returns false once stop() was called.
  bool step(double max_wait_s);
  // Thread- and signal-safe request to end run().
  void stop() { stop_requested_.store(true); }
  bool stopRequested() const { return stop_requested_.load(); }
  // start(), then step() until stop(), `duration_s` (> 0) has passed, or
  // `max_publications` (> 0) packets were sent.
  void run(double duration_s = 0, uint64_t max_publications = 0);

  // Sends the current geometry now.
  bool publishNow();
  // Handles one datagram from IPv4 address `sender` (network byte order);
  // what step() does for each packet, exposed for tests.
  Verdict handleDatagram(const char* data, size_t size, uint32_t sender);

  const Geometry& geometry() const { return geometry_; }
  const GeometryPublisherStats& stats() const { return stats_; }
  // The port processors should send to (the bound one when 0 was asked).
  uint16_t listenPort() const;

 private:
  using Clock = std::chrono::steady_clock;
  void rebuildPacket();

  Geometry geometry_;
  GeometryPublisherOptions options_;
  std::vector<uint32_t> allowed_;  // network byte order
  std::unique_ptr<UdpSocket> listener_;
  std::unique_ptr<MulticastSender> sender_;
  std::unique_ptr<RateLimitedLog> log_unknown_, log_malformed_, log_rejected_, log_send_;
  dv::ssl::SSL_WrapperPacket incoming_;  // reused for parsing
  std::string packet_;                   // serialized geometry packet
  std::string buffer_;                   // datagram buffer
  GeometryPublisherStats stats_;
  Clock::time_point next_publication_;
  bool changed_ = false;
  std::atomic<bool> stop_requested_{false};
};

// For processors: sends their calibration(s) to the publisher.
class CalibrationSender {
 public:
  // publisher_addr: IPv4 address of the publisher. local_addr: source
  // address to send from ("" = by route). Throws InputError on bad addresses.
  CalibrationSender(const std::string& publisher_addr, uint16_t port = kGeometryListenPort,
                    const std::string& local_addr = "");
  ~CalibrationSender();
  CalibrationSender(const CalibrationSender&) = delete;
  CalibrationSender& operator=(const CalibrationSender&) = delete;

  // One datagram with `field` (required by the schema) and `cameras`.
  // false when the send failed; never throws.
  bool send(const FieldModel& field, const std::vector<CameraCalibration>& cameras);
  // Raw bytes (tests, tools).
  bool sendRaw(const std::string& payload);

 private:
  std::unique_ptr<UdpSocket> socket_;
  std::vector<unsigned char> destination_;  // sockaddr_in
};

struct GeometryReceiveOptions {
  std::string group = "224.5.23.2";
  uint16_t port = 10006;
  std::string interface_addr;  // "" = the kernel's default interface
};

// For processors started without --geometry: listens on the vision group for
// at most timeout_s and returns the field with camera `camera_id`'s
// calibration (the only one in `cameras`) from the first valid geometry
// packet that has it. Invalid geometry packets are skipped. nullopt on
// timeout. Throws InputError if the group cannot be joined.
std::optional<Geometry> receiveGeometry(uint32_t camera_id, double timeout_s,
                                        const GeometryReceiveOptions& options = {});

}  // namespace dv

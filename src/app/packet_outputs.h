#pragma once
// Where detections go: multicast (through the league-style publisher, which
// also repeats the geometry every 3 s), an SSL log file, JSONL. Shared by
// every camera of a process: detection() may be called from several camera
// threads at once (one lock around the sends; a send is microseconds).
#include <fstream>
#include <memory>
#include <mutex>
#include <string>

#include "dotvision/ssl_geometry.pb.h"
#include "dotvision/ssl_wrapper.pb.h"
#include "io/ssl_log.h"
#include "net/vision_publisher.h"

namespace dv::app {

struct OutputOptions {
  bool publish = true;
  std::string group = "224.5.23.2";
  uint16_t port = 10006;
  std::string interface_addr;  // "" by route
  bool publish_geometry = true;  // false when the geometry publisher repeats it already
  std::string ssl_log;           // "" none
  std::string jsonl;             // "" none
  std::string who = "dotvision run";  // prefix of warnings
};

class PacketOutputs {
 public:
  // Throws InputError when a file cannot be opened or an explicit interface
  // cannot be used (without one, a missing route only warns: local work
  // such as recording must not stop).
  PacketOutputs(const OutputOptions& o, const ssl::SSL_GeometryData& geometry);

  void detection(const ssl::SSL_WrapperPacket& packet);
  // Repeats the geometry when due; called by detection() and by the owner's
  // idle loop, so geometry keeps going out while every camera is lost.
  void tick();
  // Replaces the geometry published from now on (a new calibration).
  void setGeometry(const ssl::SSL_GeometryData& geometry);
  // Publishes to another group, port or interface from now on (a reloaded
  // config); the files stay. Throws InputError, keeping the old target,
  // when the new one cannot be set up.
  void retarget(const OutputOptions& o);
  bool publishesGeometry() const { return o_.publish_geometry; }
  // Closes the files so they are complete (SSL log records whole). Safe twice.
  void finish();
  std::string describe() const;
  uint64_t sendFailures() const { return send_failures_; }
  // Why recording stopped ("" while it goes on or when there is none). A
  // write that fails (disk full, I/O error) stops the SSL log with one
  // warning naming the file; detection, publishing and JSONL go on.
  const std::string& recordingFailure() const { return record_failure_; }

 private:
  OutputOptions o_;
  mutable std::mutex mutex_;
  std::unique_ptr<VisionPublisher> publisher_;
  std::unique_ptr<SslLogWriter> log_;
  std::ofstream jsonl_;
  std::string buffer_;
  void stopRecording(const std::string& why);  // with mutex_ held
  void noteSendError(int error);               // with mutex_ held
  void notePublishingResumed();                // with mutex_ held
  uint64_t unsent_since_failure_ = 0;          // frames not sent since the network failed
  std::string record_failure_;
  uint64_t send_failures_ = 0;
  uint64_t jsonl_lines_ = 0;
  bool finished_ = false;
  ssl::SSL_GeometryData geometry_;  // what a new publisher starts with
};

}  // namespace dv::app

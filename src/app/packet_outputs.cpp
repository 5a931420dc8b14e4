#include "app/packet_outputs.h"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "geometry/proto_json.h"

namespace dv::app {

namespace {
int64_t unixNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}
double monotonicSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

PacketOutputs::PacketOutputs(const OutputOptions& o, const ssl::SSL_GeometryData& geometry)
    : o_(o), geometry_(geometry) {
  if (o.publish) {
    VisionPublisherOptions po;
    po.group = o.group;
    po.port = o.port;
    po.interface_addr = o.interface_addr;
    try {
      publisher_ = std::make_unique<VisionPublisher>(po);
    } catch (const InputError& e) {
      if (!o.interface_addr.empty()) throw;
      std::fprintf(stderr, "%s: warning: not publishing: %s\n", o.who.c_str(), e.what());
    }
    if (publisher_ && o.publish_geometry) {
      publisher_->setGeometry(geometry);
      publisher_->publishGeometry(monotonicSeconds());
    }
  }
  if (!o.ssl_log.empty()) {
    log_ = std::make_unique<SslLogWriter>(o.ssl_log);
    ssl::SSL_WrapperPacket g;
    g.set_source(ssl::SSL_SOURCE_SSL_VISION);
    *g.mutable_geometry() = geometry;
    try {
      log_->write(unixNs(), LogMessageType::Vision2014, g.SerializeAsString());
    } catch (const InputError& e) {
      stopRecording(e.what());
    }
  }
  if (!o.jsonl.empty()) {
    jsonl_.open(o.jsonl, std::ios::trunc);
    if (!jsonl_) throw InputError(o.jsonl, "cannot open for writing");
  }
}

void PacketOutputs::detection(const ssl::SSL_WrapperPacket& packet) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  if (publisher_) {
    const uint64_t errors_before = publisher_->sender().errorCount();
    if (publisher_->publishDetection(packet.detection())) {
      if (unsent_since_failure_ > 0) notePublishingResumed();
    } else {
      ++send_failures_;
      if (publisher_->sender().errorCount() != errors_before) noteSendError(publisher_->sender().lastErrno());
    }
    publisher_->publishGeometryIfDue(monotonicSeconds());
  }
  if (log_) {
    packet.SerializeToString(&buffer_);  // reuses the buffer's capacity
    try {
      log_->write(unixNs(), LogMessageType::Vision2014, buffer_);
    } catch (const InputError& e) {
      stopRecording(e.what());
    }
  }
  if (jsonl_.is_open()) {
    jsonl_ << toCanonicalJson(packet) << '\n';
    ++jsonl_lines_;
    if (!jsonl_) throw InputError(o_.jsonl, "write failed");
  }
}

void PacketOutputs::tick() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (publisher_ && !finished_) publisher_->publishGeometryIfDue(monotonicSeconds());
}

void PacketOutputs::retarget(const OutputOptions& o) {
  VisionPublisherOptions po;
  po.group = o.group;
  po.port = o.port;
  po.interface_addr = o.interface_addr;
  auto next = std::make_unique<VisionPublisher>(po);  // throws before anything changes
  if (o_.publish_geometry) {
    next->setGeometry(geometry_);
    next->publishGeometry(monotonicSeconds());
  }
  std::lock_guard<std::mutex> lock(mutex_);
  publisher_ = std::move(next);
  o_.group = o.group;
  o_.port = o.port;
  o_.interface_addr = o.interface_addr;
}

void PacketOutputs::setGeometry(const ssl::SSL_GeometryData& geometry) {
  std::lock_guard<std::mutex> lock(mutex_);
  geometry_ = geometry;
  if (publisher_ && o_.publish_geometry) {
    publisher_->setGeometry(geometry);
    publisher_->publishGeometry(monotonicSeconds());
  }
}

void PacketOutputs::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (log_) {
    try {
      log_->close();
    } catch (const InputError& e) {
      stopRecording(e.what());
    }
  }
  if (jsonl_.is_open()) {
    jsonl_.close();
    if (jsonl_.fail()) throw InputError(o_.jsonl, "write failed at close");
  }
}

void PacketOutputs::noteSendError(int error) {
  // A full socket buffer drops one datagram, as the network would: counted,
  // not a change of state. Anything else (no route, the interface gone)
  // fails every frame until it comes back: said once, and once when it does.
  if (error == EAGAIN || error == EWOULDBLOCK || error == ENOBUFS) return;
  if (unsent_since_failure_++ == 0)
    std::fprintf(stderr, "%s: warning: cannot publish on %s: %s; detection goes on, every frame is tried\n",
                 o_.who.c_str(), publisher_->sender().name().c_str(), std::strerror(error));
}

void PacketOutputs::notePublishingResumed() {
  std::fprintf(stderr, "%s: publishing on %s again after %llu frame(s) not sent\n", o_.who.c_str(),
               publisher_->sender().name().c_str(), static_cast<unsigned long long>(unsent_since_failure_));
  unsent_since_failure_ = 0;
}

void PacketOutputs::stopRecording(const std::string& why) {
  std::fprintf(stderr, "%s: warning: recording stopped: %s; detection and publishing go on\n", o_.who.c_str(),
               why.c_str());
  record_failure_ = why;
  log_.reset();  // closes what it can without throwing
}

std::string PacketOutputs::describe() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::string out;
  if (publisher_)
    out += "published " + std::to_string(publisher_->sender().sentCount()) + " packets to " +
           publisher_->sender().name() +
           (send_failures_ ? " (" + std::to_string(send_failures_) + " detection frames failed)" : "");
  else
    out += "not published";
  if (log_) out += "; recorded " + o_.ssl_log;
  if (!record_failure_.empty()) out += "; recording stopped: " + record_failure_;
  if (!o_.jsonl.empty()) out += "; JSONL " + o_.jsonl;
  return out;
}

}  // namespace dv::app

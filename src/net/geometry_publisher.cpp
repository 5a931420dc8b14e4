#include "net/geometry_publisher.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "net/multicast.h"

namespace dv {

// ---- a plain IPv4 UDP socket (unicast), just what the publisher needs ----

class UdpSocket {
 public:
  explicit UdpSocket(std::string name) : name_(std::move(name)) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) throw InputError(name_, std::string("cannot create a UDP socket: ") + std::strerror(errno));
  }
  ~UdpSocket() {
    if (fd_ >= 0) ::close(fd_);
  }
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;

  void bind(in_addr addr, uint16_t port) {
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_addr = addr;
    sa.sin_port = htons(port);
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) != 0) {
      throw InputError(name_, std::string("cannot bind: ") + std::strerror(errno));
    }
  }

  uint16_t localPort() const {
    sockaddr_in sa{};
    socklen_t len = sizeof sa;
    if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&sa), &len) != 0) return 0;
    return ntohs(sa.sin_port);
  }

  // True when a datagram is waiting (after at most timeout_s).
  bool wait(double timeout_s) const {
    pollfd p{fd_, POLLIN, 0};
    const int ms = int(std::ceil(std::clamp(timeout_s, 0.0, 3600.0) * 1000));
    return ::poll(&p, 1, ms) > 0 && (p.revents & POLLIN);
  }

  // One waiting datagram into `buffer` (its capacity is reused); -1 if none.
  ssize_t receive(std::string& buffer, uint32_t& sender) {
    buffer.resize(kMaxUdpPayloadBytes);
    sockaddr_in from{};
    socklen_t len = sizeof from;
    const ssize_t n = ::recvfrom(fd_, buffer.data(), buffer.size(), MSG_DONTWAIT,
                                 reinterpret_cast<sockaddr*>(&from), &len);
    if (n < 0) return -1;
    sender = from.sin_addr.s_addr;
    return n;
  }

  bool sendTo(const void* data, size_t size, const sockaddr_in& to) {
    return ::sendto(fd_, data, size, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to) ==
           ssize_t(size);
  }

  const std::string& name() const { return name_; }

 private:
  int fd_ = -1;
  std::string name_;
};

// ---- drop messages: at most one per interval, with the count in between ----

class RateLimitedLog {
 public:
  explicit RateLimitedLog(double interval_s) : interval_(interval_s) {}

  // make_message is only called when a line is written.
  template <typename MakeMessage>
  void warn(MakeMessage&& make_message) {
    const auto now = std::chrono::steady_clock::now();
    if (logged_ && std::chrono::duration<double>(now - last_).count() < interval_) {
      ++suppressed_;
      return;
    }
    std::string line = make_message();
    if (suppressed_ > 0) line += " (+" + std::to_string(suppressed_) + " more like it since the last message)";
    spdlog::warn("geometry publisher: {}", line);
    logged_ = true;
    last_ = now;
    suppressed_ = 0;
  }

 private:
  double interval_;
  bool logged_ = false;
  std::chrono::steady_clock::time_point last_;
  uint64_t suppressed_ = 0;
};

namespace {

in_addr parseIpv4(const std::string& text, const std::string& what) {
  in_addr a{};
  if (inet_pton(AF_INET, text.c_str(), &a) != 1) {
    throw InputError("command line", what + " \"" + text + "\" is not an IPv4 address");
  }
  return a;
}

std::string ipText(uint32_t addr) {
  in_addr a{};
  a.s_addr = addr;
  char buf[INET_ADDRSTRLEN] = {};
  inet_ntop(AF_INET, &a, buf, sizeof buf);
  return buf;
}

// A processor that has not seen a frame yet leaves the image size out; keep
// what an earlier calibration of that camera said.
void keepKnownImageSize(CameraCalibration& incoming, const CameraCalibration* known) {
  if (!known) return;
  if (incoming.image_width == 0) incoming.image_width = known->image_width;
  if (incoming.image_height == 0) incoming.image_height = known->image_height;
}

}  // namespace

// ---- publisher ----

GeometryPublisher::GeometryPublisher(Geometry initial, GeometryPublisherOptions options)
    : geometry_(std::move(initial)), options_(std::move(options)) {
  if (!(options_.interval_s > 0) || !std::isfinite(options_.interval_s)) {
    throw InputError("command line", "--interval must be a positive number of seconds");
  }
  if (options_.num_cameras == 0) throw InputError("command line", "--num-cameras must be at least 1");
  if (options_.allowed_sources.empty()) {
    throw InputError("command line", "no allowed source: give at least one --allow address");
  }
  for (const auto& a : options_.allowed_sources) allowed_.push_back(parseIpv4(a, "--allow").s_addr);
  for (const auto& c : geometry_.cameras) {
    if (c.camera_id >= options_.num_cameras) {
      throw InputError("command line", "--num-cameras " + std::to_string(options_.num_cameras) +
                                           " excludes camera " + std::to_string(c.camera_id) +
                                           " of the field file");
    }
  }
  std::sort(geometry_.cameras.begin(), geometry_.cameras.end(),
            [](const auto& a, const auto& b) { return a.camera_id < b.camera_id; });

  const in_addr listen = parseIpv4(options_.listen_addr, "--listen-addr");
  listener_ = std::make_unique<UdpSocket>("udp " + options_.listen_addr + ":" +
                                          std::to_string(options_.listen_port));
  listener_->bind(listen, options_.listen_port);
  sender_ = std::make_unique<MulticastSender>(options_.group, options_.port, options_.interface_addr);
  log_unknown_ = std::make_unique<RateLimitedLog>(options_.log_interval_s);
  log_malformed_ = std::make_unique<RateLimitedLog>(options_.log_interval_s);
  log_rejected_ = std::make_unique<RateLimitedLog>(options_.log_interval_s);
  log_send_ = std::make_unique<RateLimitedLog>(options_.log_interval_s);
  buffer_.reserve(kMaxUdpPayloadBytes);
  rebuildPacket();
  next_publication_ = Clock::now();
}

GeometryPublisher::~GeometryPublisher() = default;

uint16_t GeometryPublisher::listenPort() const { return listener_->localPort(); }

void GeometryPublisher::rebuildPacket() {
  dv::ssl::SSL_WrapperPacket packet;
  *packet.mutable_geometry() = toProto(geometry_);
  packet.set_source(kGeometryPacketSource);
  packet.SerializeToString(&packet_);
}

bool GeometryPublisher::publishNow() {
  if (changed_) rebuildPacket();
  changed_ = false;
  next_publication_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                         std::chrono::duration<double>(options_.interval_s));
  if (!sender_->send(packet_)) {
    ++stats_.send_errors;
    log_send_->warn([&] {
      return "cannot send on " + sender_->name() + ": " + std::strerror(sender_->lastErrno());
    });
    return false;
  }
  ++stats_.published;
  return true;
}

void GeometryPublisher::start() {
  stop_requested_.store(false);
  spdlog::info("geometry publisher: listening on {}, publishing {} camera(s) on {} every {} s",
               listener_->name().substr(0, listener_->name().rfind(':') + 1) + std::to_string(listenPort()),
               geometry_.cameras.size(), sender_->name(), options_.interval_s);
  publishNow();
}

GeometryPublisher::Verdict GeometryPublisher::handleDatagram(const char* data, size_t size,
                                                             uint32_t sender) {
  ++stats_.datagrams;
  if (std::find(allowed_.begin(), allowed_.end(), sender) == allowed_.end()) {
    ++stats_.unknown_source;
    log_unknown_->warn([&] {
      return "dropped a datagram from " + ipText(sender) + ": not an allowed source (see --allow)";
    });
    return Verdict::UnknownSource;
  }
  // Partial parse: the processor's field is not used, so a packet that omits
  // it is fine as long as each calibration is complete.
  const char* problem = nullptr;
  if (!incoming_.ParsePartialFromArray(data, int(size))) {
    problem = "does not parse as SSL_WrapperPacket";
  } else if (!incoming_.has_geometry()) {
    problem = "carries no geometry";
  } else if (incoming_.geometry().calib_size() == 0) {
    problem = "carries no camera calibration";
  } else {
    for (const auto& c : incoming_.geometry().calib()) {
      if (!c.IsInitialized()) problem = "has a calibration that lacks required fields";
    }
  }
  if (problem) {
    ++stats_.malformed;
    log_malformed_->warn([&] {
      return "dropped a " + std::to_string(size) + "-byte datagram from " + ipText(sender) + ": it " + problem;
    });
    return Verdict::Malformed;
  }

  bool any_accepted = false;
  for (const auto& m : incoming_.geometry().calib()) {
    CameraCalibration c = calibrationFromProto(m);
    std::optional<std::string> reason;
    if (c.camera_id >= options_.num_cameras) {
      reason = "camera id outside 0.." + std::to_string(options_.num_cameras - 1) + " (--num-cameras)";
    } else {
      reason = calibrationProblem(m);
    }
    if (reason) {
      ++stats_.rejected;
      log_rejected_->warn([&] {
        return "rejected the calibration of camera " + std::to_string(c.camera_id) + " from " +
               ipText(sender) + ": " + *reason;
      });
      continue;
    }
    ++stats_.accepted;
    any_accepted = true;
    auto it = std::find_if(geometry_.cameras.begin(), geometry_.cameras.end(),
                           [&](const auto& k) { return k.camera_id == c.camera_id; });
    keepKnownImageSize(c, it == geometry_.cameras.end() ? nullptr : &*it);
    if (it == geometry_.cameras.end()) {
      spdlog::info("geometry publisher: camera {} calibrated by {}", c.camera_id, ipText(sender));
      geometry_.cameras.push_back(c);
      std::sort(geometry_.cameras.begin(), geometry_.cameras.end(),
                [](const auto& a, const auto& b) { return a.camera_id < b.camera_id; });
      changed_ = true;
    } else if (*it != c) {
      spdlog::info("geometry publisher: camera {} recalibrated by {}", c.camera_id, ipText(sender));
      *it = c;
      changed_ = true;
    }
  }
  return any_accepted ? Verdict::Accepted : Verdict::Rejected;
}

bool GeometryPublisher::step(double max_wait_s) {
  if (stop_requested_.load()) return false;
  auto due = [&] { return changed_ || Clock::now() >= next_publication_; };
  if (due()) publishNow();
  const double until_due = std::chrono::duration<double>(next_publication_ - Clock::now()).count();
  if (listener_->wait(std::min(max_wait_s, std::max(0.0, until_due)))) {
    // A bounded batch, so a flood cannot starve the periodic publication.
    uint32_t sender = 0;
    for (int i = 0; i < 256; ++i) {
      const ssize_t n = listener_->receive(buffer_, sender);
      if (n < 0) break;
      handleDatagram(buffer_.data(), size_t(n), sender);
    }
  }
  if (due()) publishNow();
  return !stop_requested_.load();
}

void GeometryPublisher::run(double duration_s, uint64_t max_publications) {
  const auto begin = Clock::now();
  start();
  while (!stop_requested_.load()) {
    if (max_publications > 0 && stats_.published >= max_publications) break;
    double wait = 0.2;  // bounds how late stop() is noticed
    if (duration_s > 0) {
      const double left = duration_s - std::chrono::duration<double>(Clock::now() - begin).count();
      if (left <= 0) break;
      wait = std::min(wait, left);
    }
    step(wait);
  }
}

// ---- processors' side ----

CalibrationSender::CalibrationSender(const std::string& publisher_addr, uint16_t port,
                                     const std::string& local_addr) {
  const in_addr to = parseIpv4(publisher_addr, "geometry publisher address");
  socket_ = std::make_unique<UdpSocket>("udp " + publisher_addr + ":" + std::to_string(port));
  if (!local_addr.empty()) socket_->bind(parseIpv4(local_addr, "local address"), 0);
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_addr = to;
  sa.sin_port = htons(port);
  destination_.resize(sizeof sa);
  std::memcpy(destination_.data(), &sa, sizeof sa);
}

CalibrationSender::~CalibrationSender() = default;

bool CalibrationSender::sendRaw(const std::string& payload) {
  sockaddr_in sa{};
  std::memcpy(&sa, destination_.data(), sizeof sa);
  return socket_->sendTo(payload.data(), payload.size(), sa);
}

bool CalibrationSender::send(const FieldModel& field, const std::vector<CameraCalibration>& cameras) {
  dv::ssl::SSL_WrapperPacket packet;
  *packet.mutable_geometry() = toProto(Geometry{field, cameras});
  packet.set_source(kGeometryPacketSource);
  return sendRaw(packet.SerializeAsString());
}

std::optional<Geometry> receiveGeometry(uint32_t camera_id, double timeout_s,
                                        const GeometryReceiveOptions& options) {
  MulticastReceiver rx(options.group, options.port, options.interface_addr);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                               std::chrono::duration<double>(std::max(0.0, timeout_s)));
  std::string payload;
  dv::ssl::SSL_WrapperPacket packet;
  bool warned = false;
  while (true) {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) return std::nullopt;
    if (!rx.receive(left, payload)) continue;  // timeout (ends at the top) or a failed read
    // Partial parse and the check: protobuf's own would print a line per
    // noise packet that lacks required fields.
    if (!packet.ParsePartialFromString(payload) || !packet.IsInitialized() || !packet.has_geometry()) {
      continue;  // detections, noise
    }
    const auto& data = packet.geometry();
    const auto it = std::find_if(data.calib().begin(), data.calib().end(),
                                 [&](const auto& c) { return c.camera_id() == camera_id; });
    if (it == data.calib().end()) continue;
    // Only the field and this camera matter here; another camera's bad
    // calibration is not this processor's problem.
    Geometry g;
    g.field = fieldFromProto(data.field());
    g.cameras = {calibrationFromProto(*it)};
    auto problem = fieldProblem(g.field);
    if (!problem) problem = calibrationProblem(*it);
    if (problem) {
      if (!warned) spdlog::warn("{}: ignoring geometry for camera {}: {}", rx.name(), camera_id, *problem);
      warned = true;
      continue;
    }
    return g;
  }
}

}  // namespace dv

#include "net/multicast.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>

#include "core/error.h"

namespace dv {
namespace {

std::string endpointName(const std::string& group, uint16_t port) {
  return "udp " + group + ":" + std::to_string(port);
}

std::string errnoText(const std::string& what) { return what + ": " + std::strerror(errno); }

in_addr parseGroup(const std::string& group, const std::string& name) {
  in_addr addr{};
  if (inet_pton(AF_INET, group.c_str(), &addr) != 1) {
    throw InputError(name, "\"" + group + "\" is not an IPv4 address");
  }
  if (!IN_MULTICAST(ntohl(addr.s_addr))) {
    throw InputError(name, "\"" + group + "\" is not a multicast address (224.0.0.0/4)");
  }
  return addr;
}

in_addr parseInterface(const std::string& interface_addr, const std::string& name) {
  in_addr addr{};
  addr.s_addr = htonl(INADDR_ANY);
  if (!interface_addr.empty() && inet_pton(AF_INET, interface_addr.c_str(), &addr) != 1) {
    throw InputError(name, "interface \"" + interface_addr + "\" is not an IPv4 address");
  }
  return addr;
}

// Closes the socket if construction fails half-way.
struct SocketGuard {
  int fd;
  ~SocketGuard() {
    if (fd >= 0) ::close(fd);
  }
  int release() {
    int f = fd;
    fd = -1;
    return f;
  }
};

}  // namespace

// ---------------------------------------------------------------- sender

MulticastSender::MulticastSender(const std::string& group, uint16_t port,
                                 const std::string& interface_addr)
    : name_(endpointName(group, port)) {
  const in_addr group_addr = parseGroup(group, name_);
  const in_addr iface = parseInterface(interface_addr, name_);

  SocketGuard guard{::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0)};
  if (guard.fd < 0) throw InputError(name_, errnoText("cannot create a UDP socket"));
  // ssl-vision's settings: TTL 32, loopback on.
  const unsigned char ttl = 32;
  const unsigned char loop = 1;
  if (::setsockopt(guard.fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl) != 0 ||
      ::setsockopt(guard.fd, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop) != 0) {
    throw InputError(name_, errnoText("cannot set multicast TTL/loopback"));
  }
  if (!interface_addr.empty() &&
      ::setsockopt(guard.fd, IPPROTO_IP, IP_MULTICAST_IF, &iface, sizeof iface) != 0) {
    throw InputError(name_, errnoText("cannot send on interface " + interface_addr));
  }
  sockaddr_in dest{};
  dest.sin_family = AF_INET;
  dest.sin_port = htons(port);
  dest.sin_addr = group_addr;
  destination_.resize(sizeof dest);
  std::memcpy(destination_.data(), &dest, sizeof dest);
  fd_ = guard.release();
}

MulticastSender::~MulticastSender() {
  if (fd_ >= 0) ::close(fd_);
}

bool MulticastSender::send(const std::string& payload) {
  return send(payload.data(), payload.size());
}

bool MulticastSender::send(const void* data, size_t size) {
  if (size > kMaxUdpPayloadBytes) {
    ++errors_;
    last_errno_ = EMSGSIZE;
    return false;
  }
  // MSG_DONTWAIT: a full socket buffer must not stall the frame loop; the
  // datagram is dropped and counted instead, as the network would.
  ssize_t n = ::sendto(fd_, data, size, MSG_DONTWAIT,
                       reinterpret_cast<const sockaddr*>(destination_.data()),
                       socklen_t(destination_.size()));
  if (n != ssize_t(size)) {
    ++errors_;
    last_errno_ = n < 0 ? errno : EMSGSIZE;
    return false;
  }
  ++sent_;
  return true;
}

// ---------------------------------------------------------------- receiver

MulticastReceiver::MulticastReceiver(const std::string& group, uint16_t port,
                                     const std::string& interface_addr)
    : name_(endpointName(group, port)), buffer_(kMaxUdpPayloadBytes + 1) {
  const in_addr group_addr = parseGroup(group, name_);
  const in_addr iface = parseInterface(interface_addr, name_);

  SocketGuard guard{::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0)};
  if (guard.fd < 0) throw InputError(name_, errnoText("cannot create a UDP socket"));
  const int on = 1;
  if (::setsockopt(guard.fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on) != 0 ||
      ::setsockopt(guard.fd, SOL_SOCKET, SO_REUSEPORT, &on, sizeof on) != 0) {
    throw InputError(name_, errnoText("cannot share the port (SO_REUSEADDR/SO_REUSEPORT)"));
  }
#ifdef IP_MULTICAST_ALL
  // Linux otherwise delivers every group any socket on this host joined for
  // the port; we want only our own group.
  const int off = 0;
  ::setsockopt(guard.fd, IPPROTO_IP, IP_MULTICAST_ALL, &off, sizeof off);
#endif
  sockaddr_in local{};
  local.sin_family = AF_INET;
  local.sin_port = htons(port);
  local.sin_addr.s_addr = htonl(INADDR_ANY);
  if (::bind(guard.fd, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0) {
    throw InputError(name_, errnoText("cannot bind port " + std::to_string(port)));
  }
  ip_mreq membership{};
  membership.imr_multiaddr = group_addr;
  membership.imr_interface = iface;
  if (::setsockopt(guard.fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) != 0) {
    // ENODEV usually means no interface/route for multicast: either pass
    // the interface address explicitly or add a route for 224.0.0.0/4.
    throw InputError(name_, errnoText("cannot join the group on interface " +
                                      (interface_addr.empty() ? std::string("(default)")
                                                              : interface_addr)));
  }
  fd_ = guard.release();
}

MulticastReceiver::~MulticastReceiver() {
  if (fd_ >= 0) ::close(fd_);
}

bool MulticastReceiver::receive(double timeout_s, std::string& payload,
                                std::string* sender_addr) {
  using Clock = std::chrono::steady_clock;
  if (!(timeout_s >= 0)) timeout_s = 0;  // also catches NaN
  const auto deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(std::min(timeout_s, 1e6)));
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    // Round up so a short positive timeout still waits at least 1 ms.
    const int wait_ms = left.count() <= 0 ? 0 : int(left.count()) + 1;
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, wait_ms);
    if (ready < 0) {
      if (errno == EINTR && Clock::now() < deadline) continue;
      ++errors_;
      return false;
    }
    if (ready == 0) return false;  // timeout

    sockaddr_in from{};
    socklen_t from_len = sizeof from;
    const ssize_t n = ::recvfrom(fd_, buffer_.data(), buffer_.size(), MSG_DONTWAIT,
                                 reinterpret_cast<sockaddr*>(&from), &from_len);
    if (n < 0) {
      if ((errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) && Clock::now() < deadline) {
        continue;
      }
      if (errno != EAGAIN && errno != EWOULDBLOCK) ++errors_;
      return false;
    }
    payload.assign(buffer_.data(), size_t(n));
    if (sender_addr) {
      char text[INET_ADDRSTRLEN] = {};
      ::inet_ntop(AF_INET, &from.sin_addr, text, sizeof text);
      *sender_addr = std::string(text) + ":" + std::to_string(ntohs(from.sin_port));
    }
    ++received_;
    return true;
  }
}

std::optional<std::string> MulticastReceiver::receive(double timeout_s, std::string* sender_addr) {
  std::string payload;
  if (!receive(timeout_s, payload, sender_addr)) return std::nullopt;
  return payload;
}

}  // namespace dv

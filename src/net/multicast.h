#pragma once
// IPv4 UDP multicast as the league uses it: one serialized protobuf message
// per datagram, TTL 32, loopback on (so receivers on the sending host also
// get the packets).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace dv {

// Largest payload one IPv4 UDP datagram can carry.
inline constexpr size_t kMaxUdpPayloadBytes = 65507;

class MulticastSender {
 public:
  // group: an IPv4 multicast address (224.0.0.0/4). interface_addr: the
  // local IPv4 address of the interface to send on ("" = the kernel's
  // choice by route; "127.0.0.1" = loopback only). Throws InputError naming
  // "udp <group>:<port>" on a bad address or when the socket cannot be set
  // up.
  MulticastSender(const std::string& group = "224.5.23.2", uint16_t port = 10006,
                  const std::string& interface_addr = "");
  ~MulticastSender();
  MulticastSender(const MulticastSender&) = delete;
  MulticastSender& operator=(const MulticastSender&) = delete;

  // Sends one datagram. Returns false and counts the failure (oversized
  // payload, full socket buffer, no route...); never throws.
  bool send(const std::string& payload);
  bool send(const void* data, size_t size);

  uint64_t sentCount() const { return sent_; }
  uint64_t errorCount() const { return errors_; }
  // errno of the most recent failure (0 if none), for a diagnostic line.
  int lastErrno() const { return last_errno_; }
  // "udp <group>:<port>", the name used in messages.
  const std::string& name() const { return name_; }

 private:
  int fd_ = -1;
  std::string name_;
  std::vector<unsigned char> destination_;  // sockaddr_in, kept opaque here
  uint64_t sent_ = 0;
  uint64_t errors_ = 0;
  int last_errno_ = 0;
};

class MulticastReceiver {
 public:
  // Binds port with SO_REUSEADDR and SO_REUSEPORT (several receivers, also
  // in other processes, can share it) and joins `group` on the interface
  // with local address interface_addr ("" = the kernel's default
  // interface). Only datagrams for the joined group are delivered. Throws
  // InputError naming "udp <group>:<port>" on failure.
  MulticastReceiver(const std::string& group, uint16_t port,
                    const std::string& interface_addr = "");
  ~MulticastReceiver();
  MulticastReceiver(const MulticastReceiver&) = delete;
  MulticastReceiver& operator=(const MulticastReceiver&) = delete;

  // Waits at most timeout_s (0 = just poll) for one datagram. nullopt on
  // timeout or error (see errorCount()). sender_addr, if given, receives
  // "a.b.c.d:port" of the sender.
  std::optional<std::string> receive(double timeout_s, std::string* sender_addr = nullptr);
  // The same into a caller-owned buffer whose capacity is reused (no
  // allocation per datagram once it has grown); false on timeout or error.
  bool receive(double timeout_s, std::string& payload, std::string* sender_addr = nullptr);

  uint64_t receivedCount() const { return received_; }
  uint64_t errorCount() const { return errors_; }
  const std::string& name() const { return name_; }

 private:
  int fd_ = -1;
  std::string name_;
  std::vector<char> buffer_;
  uint64_t received_ = 0;
  uint64_t errors_ = 0;
};

}  // namespace dv

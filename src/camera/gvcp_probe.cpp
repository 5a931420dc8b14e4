#include "camera/gvcp_probe.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>

namespace dv {

namespace {

constexpr uint16_t kGvcpPort = 3956;
constexpr uint8_t kCommandKey = 0x42, kAckRequired = 0x01;
constexpr uint16_t kReadRegCmd = 0x0080, kReadRegAck = 0x0081;
constexpr uint32_t kVersionRegister = 0x0000;

void put16(uint8_t* p, uint16_t v) { p[0] = v >> 8, p[1] = v & 0xff; }
uint16_t get16(const uint8_t* p) { return static_cast<uint16_t>(p[0] << 8 | p[1]); }

std::atomic<uint16_t> g_request_id{0};

uint16_t nextRequestId() {
  uint16_t id = ++g_request_id;
  return id ? id : ++g_request_id;  // 0 is not a valid request id
}

}  // namespace

bool gvcpCameraAnswers(const std::string& ip, double timeout_s, int attempts) {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(kGvcpPort);
  if (inet_pton(AF_INET, ip.c_str(), &to.sin_addr) != 1) return false;
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  bool answered = false;
  for (int attempt = 0; attempt < attempts && !answered; ++attempt) {
    const uint16_t id = nextRequestId();
    // Command header (key, flags, command, payload length, request id), then the address.
    uint8_t cmd[12] = {kCommandKey, kAckRequired};
    put16(cmd + 2, kReadRegCmd);
    put16(cmd + 4, 4);
    put16(cmd + 6, id);
    put16(cmd + 8, kVersionRegister >> 16);
    put16(cmd + 10, kVersionRegister & 0xffff);
    if (::sendto(fd, cmd, sizeof cmd, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to) != sizeof cmd) break;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    for (;;) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) break;
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
      uint8_t ack[64];
      const ssize_t n = ::recv(fd, ack, sizeof ack, 0);
      // Ack header: status, answer, payload length, ack id.
      if (n >= 8 && get16(ack + 2) == kReadRegAck && get16(ack + 6) == id) {
        answered = true;
        break;
      }
    }
  }
  ::close(fd);
  return answered;
}

}  // namespace dv

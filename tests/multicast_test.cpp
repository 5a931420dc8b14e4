// Real UDP multicast on the loopback interface, no mocks. Every test joins
// and sends on 127.0.0.1 explicitly, so no multicast route is needed (the
// sandbox's default route points at eth0 and lo lacks the MULTICAST flag,
// yet loopback delivery works when the interface is named). Ports are
// random in 41000..48999 and payloads carry a random nonce, so parallel runs
// of this suite cannot confuse each other's datagrams.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <random>
#include <string>

#include "core/error.h"
#include "dotvision/ssl_wrapper.pb.h"
#include "net/multicast.h"
#include "net/vision_publisher.h"

namespace dv {
namespace {

constexpr char kLoopback[] = "127.0.0.1";
constexpr char kGroup[] = "224.5.23.2";

std::mt19937_64& rng() {
  static std::mt19937_64 r(std::random_device{}() ^ uint64_t(::getpid()) << 32);
  return r;
}

uint16_t randomPort() { return uint16_t(41000 + rng()() % 8000); }

std::string readText(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// What a failing environment looks like, for the failure message.
std::string environmentReport() {
  return "lo flags (hex, 0x1000 = IFF_MULTICAST): " + readText("/sys/class/net/lo/flags") +
         "IPv4 routes (/proc/net/route):\n" + readText("/proc/net/route") +
         "If loopback multicast is unavailable, try: ip link set lo multicast on && "
         "ip route add 224.0.0.0/4 dev lo";
}

// Receives until a datagram equal to `want` arrives or the deadline passes;
// foreign datagrams (another run on the same port) are skipped.
bool receiveExactly(MulticastReceiver& rx, const std::string& want, double timeout_s,
                    std::string* sender = nullptr) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (int i = 0; i < 1000; ++i) {
    const double left =
        std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) return false;
    auto got = rx.receive(left, sender);
    if (!got) return false;
    if (*got == want) return true;
  }
  return false;
}

std::string nonce() { return "dv-test-" + std::to_string(rng()()); }

// Probe run once: does a datagram sent on 127.0.0.1 reach a member there?
bool loopbackMulticastWorks() {
  static const bool works = [] {
    try {
      const uint16_t port = randomPort();
      MulticastReceiver rx(kGroup, port, kLoopback);
      MulticastSender tx(kGroup, port, kLoopback);
      const std::string probe = nonce();
      for (int attempt = 0; attempt < 3; ++attempt) {
        tx.send(probe);
        if (receiveExactly(rx, probe, 0.5)) return true;
      }
    } catch (const InputError&) {
    }
    return false;
  }();
  return works;
}

#define REQUIRE_LOOPBACK_MULTICAST()                                                   \
  if (!loopbackMulticastWorks())                                                       \
  GTEST_SKIP() << "loopback multicast unavailable here; see "                          \
                  "MulticastEnvironment.LoopbackDeliversMulticast"

TEST(MulticastEnvironment, LoopbackDeliversMulticast) {
  EXPECT_TRUE(loopbackMulticastWorks())
      << "a datagram sent to " << kGroup << " on interface 127.0.0.1 did not arrive.\n"
      << environmentReport();
}

dv::ssl::SSL_WrapperPacket sampleDetectionPacket(uint32_t frame_number) {
  dv::ssl::SSL_WrapperPacket packet;
  packet.set_source(dv::ssl::SSL_SOURCE_SSL_VISION);
  auto* frame = packet.mutable_detection();
  frame->set_frame_number(frame_number);
  frame->set_t_capture(1700000000.25);
  frame->set_t_sent(1700000000.26);
  frame->set_camera_id(3);
  auto* ball = frame->add_balls();
  ball->set_confidence(0.9f);
  ball->set_x(120.5f);
  ball->set_y(-33.0f);
  ball->set_pixel_x(400.0f);
  ball->set_pixel_y(300.0f);
  auto* robot = frame->add_robots_blue();
  robot->set_confidence(1.0f);
  robot->set_robot_id(7);
  robot->set_x(-1000.0f);
  robot->set_y(500.0f);
  robot->set_orientation(1.5f);
  robot->set_pixel_x(10.0f);
  robot->set_pixel_y(20.0f);
  return packet;
}

TEST(Multicast, WrapperPacketTravelsOverLoopback) {
  REQUIRE_LOOPBACK_MULTICAST();
  const uint16_t port = randomPort();
  MulticastReceiver rx(kGroup, port, kLoopback);
  MulticastSender tx(kGroup, port, kLoopback);
  const uint32_t frame_number = uint32_t(rng()());
  const std::string bytes = sampleDetectionPacket(frame_number).SerializeAsString();

  ASSERT_TRUE(tx.send(bytes));
  std::string sender;
  ASSERT_TRUE(receiveExactly(rx, bytes, 2.0, &sender));
  EXPECT_EQ(sender.rfind("127.0.0.1:", 0), 0u) << sender;

  dv::ssl::SSL_WrapperPacket decoded;
  ASSERT_TRUE(decoded.ParseFromString(bytes));
  EXPECT_EQ(decoded.detection().frame_number(), frame_number);
  EXPECT_EQ(decoded.detection().robots_blue(0).robot_id(), 7u);
  EXPECT_EQ(tx.sentCount(), 1u);
  EXPECT_EQ(tx.errorCount(), 0u);
}

TEST(Multicast, SeveralReceiversShareOnePort) {
  REQUIRE_LOOPBACK_MULTICAST();
  const uint16_t port = randomPort();
  MulticastReceiver a(kGroup, port, kLoopback);
  MulticastReceiver b(kGroup, port, kLoopback);
  MulticastSender tx(kGroup, port, kLoopback);
  const std::string payload = nonce();
  ASSERT_TRUE(tx.send(payload));
  EXPECT_TRUE(receiveExactly(a, payload, 2.0));
  EXPECT_TRUE(receiveExactly(b, payload, 2.0));
}

TEST(Multicast, OnlyTheJoinedGroupIsDelivered) {
  REQUIRE_LOOPBACK_MULTICAST();
  const uint16_t port = randomPort();
  MulticastReceiver ours(kGroup, port, kLoopback);
  MulticastReceiver other("239.255.41.7", port, kLoopback);
  MulticastSender tx(kGroup, port, kLoopback);
  const std::string payload = nonce();
  ASSERT_TRUE(tx.send(payload));
  EXPECT_TRUE(receiveExactly(ours, payload, 2.0));
  EXPECT_FALSE(receiveExactly(other, payload, 0.2));
}

TEST(Multicast, BurstArrivesInOrder) {
  REQUIRE_LOOPBACK_MULTICAST();
  const uint16_t port = randomPort();
  MulticastReceiver rx(kGroup, port, kLoopback);
  MulticastSender tx(kGroup, port, kLoopback);
  const std::string tag = nonce() + "#";
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(tx.send(tag + std::to_string(i)));
  std::string payload;
  int expected = 0;
  for (int i = 0; i < 200 && expected < 50; ++i) {
    if (!rx.receive(2.0, payload)) break;
    if (payload.rfind(tag, 0) != 0) continue;  // someone else's datagram
    EXPECT_EQ(payload, tag + std::to_string(expected));
    ++expected;
  }
  EXPECT_EQ(expected, 50);
}

TEST(Multicast, LargestDatagramArrivesIntact) {
  REQUIRE_LOOPBACK_MULTICAST();
  const uint16_t port = randomPort();
  MulticastReceiver rx(kGroup, port, kLoopback);
  MulticastSender tx(kGroup, port, kLoopback);
  std::string payload = nonce();
  payload.resize(kMaxUdpPayloadBytes, 'g');
  ASSERT_TRUE(tx.send(payload));
  EXPECT_TRUE(receiveExactly(rx, payload, 2.0));
}

TEST(Multicast, OversizedPayloadIsCountedNotThrown) {
  MulticastSender tx(kGroup, randomPort(), kLoopback);
  EXPECT_FALSE(tx.send(std::string(kMaxUdpPayloadBytes + 1, 'x')));
  EXPECT_EQ(tx.errorCount(), 1u);
  EXPECT_EQ(tx.sentCount(), 0u);
  EXPECT_NE(tx.lastErrno(), 0);
}

TEST(Multicast, ReceiveTimesOut) {
  MulticastReceiver rx(kGroup, randomPort(), kLoopback);
  const auto start = std::chrono::steady_clock::now();
  std::string payload;
  // Nothing is sent here; any datagram would be a stranger's (same random
  // port), which a bounded loop tolerates.
  int received = 0;
  for (int i = 0; i < 5 && rx.receive(0.05, payload); ++i) ++received;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(received, 5);
  EXPECT_GE(elapsed, 0.045);
}

// Expects an InputError whose message contains `part`.
template <class Fn>
void expectInputError(Fn fn, const std::string& part) {
  try {
    fn();
    ADD_FAILURE() << "no InputError thrown";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(Multicast, BadGroupNamesTheEndpoint) {
  for (const char* group : {"300.1.2.3", "not-an-address", "10.0.0.1", ""}) {
    const std::string name = std::string("udp ") + group + ":41999";
    expectInputError([&] { MulticastSender tx(group, 41999); }, name);
    expectInputError([&] { MulticastReceiver rx(group, 41999); }, name);
  }
}

TEST(Multicast, BadInterfaceIsRefused) {
  expectInputError([] { MulticastReceiver rx(kGroup, 41999, "eth-zero"); }, "interface");
  expectInputError([] { MulticastSender tx(kGroup, 41999, "eth-zero"); }, "interface");
  // A well-formed address that belongs to no local interface.
  expectInputError([] { MulticastReceiver rx(kGroup, 41999, "203.0.113.77"); },
                   "udp 224.5.23.2:41999");
}

TEST(Multicast, PortHeldExclusivelyCannotBeBound) {
  // A plain socket without SO_REUSEADDR/PORT holds the port exclusively.
  int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in local{};
  local.sin_family = AF_INET;
  local.sin_addr.s_addr = htonl(INADDR_ANY);
  uint16_t port = 0;
  for (int attempt = 0; attempt < 20 && port == 0; ++attempt) {
    uint16_t candidate = randomPort();
    local.sin_port = htons(candidate);
    if (::bind(fd, reinterpret_cast<sockaddr*>(&local), sizeof local) == 0) port = candidate;
  }
  ASSERT_NE(port, 0);
  expectInputError([&] { MulticastReceiver rx(kGroup, port, kLoopback); }, "cannot bind");
  ::close(fd);
}


// ---------------------------------------------------------------- publisher

TEST(VisionPublisher, DetectionAndGeometryTravelInSeparateWrappers) {
  REQUIRE_LOOPBACK_MULTICAST();
  VisionPublisherOptions options;
  options.port = randomPort();
  options.interface_addr = kLoopback;
  MulticastReceiver rx(options.group, options.port, kLoopback);
  VisionPublisher publisher(options);

  const uint32_t frame_number = uint32_t(rng()());
  ASSERT_TRUE(publisher.publishDetection(sampleDetectionPacket(frame_number).detection()));
  dv::ssl::SSL_GeometryData geometry;
  auto* field = geometry.mutable_field();
  field->set_field_length(9000);
  field->set_field_width(6000);
  field->set_goal_width(1000);
  field->set_goal_depth(180);
  field->set_boundary_width(int32_t(300 + rng()() % 1000));  // tells our packet apart
  ASSERT_TRUE(publisher.setGeometry(geometry));
  ASSERT_TRUE(publisher.publishGeometryIfDue(100.0));

  bool saw_detection = false, saw_geometry = false;
  std::string payload;
  for (int i = 0; i < 100 && !(saw_detection && saw_geometry); ++i) {
    if (!rx.receive(2.0, payload)) break;
    dv::ssl::SSL_WrapperPacket packet;
    if (!packet.ParseFromString(payload)) continue;
    EXPECT_EQ(packet.source(), dv::ssl::SSL_SOURCE_SSL_VISION);
    EXPECT_NE(packet.has_detection(), packet.has_geometry()) << "exactly one per datagram";
    if (packet.has_detection() && packet.detection().frame_number() == frame_number) {
      saw_detection = true;
      EXPECT_EQ(packet.detection().robots_blue_size(), 1);
    }
    if (packet.has_geometry() &&
        packet.geometry().field().boundary_width() == field->boundary_width()) {
      saw_geometry = true;
    }
  }
  EXPECT_TRUE(saw_detection);
  EXPECT_TRUE(saw_geometry);
}

TEST(VisionPublisher, GeometryRepeatsAtTheInterval) {
  VisionPublisherOptions options;
  options.port = randomPort();
  options.interface_addr = kLoopback;
  options.geometry_interval_s = 3.0;
  VisionPublisher publisher(options);
  EXPECT_FALSE(publisher.publishGeometryIfDue(0.0)) << "nothing to send yet";
  dv::ssl::SSL_GeometryData geometry;
  EXPECT_FALSE(publisher.setGeometry(geometry)) << "required field sizes missing";
  auto* field = geometry.mutable_field();
  for (auto set : {&dv::ssl::SSL_GeometryFieldSize::set_field_length,
                   &dv::ssl::SSL_GeometryFieldSize::set_field_width,
                   &dv::ssl::SSL_GeometryFieldSize::set_goal_width,
                   &dv::ssl::SSL_GeometryFieldSize::set_goal_depth,
                   &dv::ssl::SSL_GeometryFieldSize::set_boundary_width}) {
    (field->*set)(100);
  }
  ASSERT_TRUE(publisher.setGeometry(geometry));
  EXPECT_TRUE(publisher.publishGeometryIfDue(10.0));  // first time: at once
  EXPECT_FALSE(publisher.publishGeometryIfDue(11.0));
  EXPECT_FALSE(publisher.publishGeometryIfDue(12.9));
  EXPECT_TRUE(publisher.publishGeometryIfDue(13.0));
  EXPECT_FALSE(publisher.publishGeometryIfDue(14.0));
  EXPECT_EQ(publisher.sender().sentCount(), 2u);
}

TEST(VisionPublisher, IncompleteFrameIsNotSent) {
  VisionPublisherOptions options;
  options.port = randomPort();
  options.interface_addr = kLoopback;
  VisionPublisher publisher(options);
  publisher.detection().set_frame_number(1);  // t_capture, t_sent, camera_id missing
  EXPECT_FALSE(publisher.sendDetection());
  EXPECT_EQ(publisher.droppedInvalid(), 1u);
  EXPECT_EQ(publisher.sender().sentCount(), 0u);
  EXPECT_FALSE(publisher.detection().has_frame_number()) << "cleared for the next frame";
}

}  // namespace
}  // namespace dv

// Geometry publisher on real loopback sockets: processors' calibrations are
// merged and published on the vision group; malformed packets, unknown
// sources and implausible calibrations are dropped and counted; processors
// can take their geometry from the network; the CLI stops by itself.
// Everything sends and joins on 127.0.0.1 explicitly (no multicast route is
// needed), the listen port is chosen by the kernel and the multicast port
// is random, so parallel runs do not see each other's packets.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <thread>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <cstring>
#include <sstream>

#include "core/error.h"
#include "dotvision/ssl_wrapper.pb.h"
#include "net/geometry_publisher.h"
#include "net/multicast.h"

namespace dv {
namespace {

constexpr char kLoopback[] = "127.0.0.1";
constexpr char kGroup[] = "224.5.23.2";

uint16_t randomPort() {
  static std::mt19937_64 rng(std::random_device{}() ^ uint64_t(::getpid()) << 20);
  return uint16_t(49200 + rng() % 8000);
}

GeometryPublisherOptions loopbackOptions() {
  GeometryPublisherOptions o;
  o.listen_addr = kLoopback;
  o.listen_port = 0;
  o.allowed_sources = {kLoopback};
  o.num_cameras = 4;
  o.interval_s = 30;  // tests publish on change or explicitly
  o.group = kGroup;
  o.port = randomPort();
  o.interface_addr = kLoopback;
  o.log_interval_s = 60;
  return o;
}

CameraCalibration overheadCamera(uint32_t id, double x) {
  Eigen::Matrix3d down;
  down << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  auto c = CameraCalibration::fromPose(id, 1100, 1224, 1024, 0.05, down, {x, 0, 4000});
  c.image_width = 2448;
  c.image_height = 2048;
  return c;
}

// Steps the publisher until `done` or about two seconds have passed.
template <typename Done>
bool stepUntil(GeometryPublisher& p, Done done) {
  for (int i = 0; i < 40 && !done(); ++i) p.step(0.05);
  return done();
}

// The next geometry packet from our publisher (source and field checked by
// the caller) whose calibrations satisfy `want`, within timeout_s.
template <typename Want>
std::optional<ssl::SSL_WrapperPacket> receiveGeometryPacket(MulticastReceiver& rx, Want want,
                                                            double timeout_s = 2.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::string payload;
  for (int i = 0; i < 1000; ++i) {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0 || !rx.receive(left, payload)) return std::nullopt;
    ssl::SSL_WrapperPacket packet;
    if (packet.ParseFromString(payload) && packet.has_geometry() && want(packet.geometry())) return packet;
  }
  return std::nullopt;
}

const ssl::SSL_GeometryCameraCalibration* findCalib(const ssl::SSL_GeometryData& g, uint32_t id) {
  for (const auto& c : g.calib()) {
    if (c.camera_id() == id) return &c;
  }
  return nullptr;
}

TEST(GeometryPublisher, AcceptedCalibrationIsPublished) {
  const auto options = loopbackOptions();
  MulticastReceiver rx(kGroup, options.port, kLoopback);
  GeometryPublisher publisher(Geometry{FieldModel::divisionA(), {overheadCamera(0, -3000)}}, options);
  publisher.start();

  CalibrationSender processor(kLoopback, publisher.listenPort());
  const CameraCalibration mine = overheadCamera(2, 3000);
  ASSERT_TRUE(processor.send(FieldModel::divisionB(), {mine}));  // its field is ignored
  ASSERT_TRUE(stepUntil(publisher, [&] { return publisher.stats().accepted == 1; }));

  const auto packet =
      receiveGeometryPacket(rx, [](const ssl::SSL_GeometryData& g) { return findCalib(g, 2) != nullptr; });
  ASSERT_TRUE(packet.has_value()) << "no geometry packet with camera 2 arrived";
  EXPECT_FALSE(packet->has_detection());
  EXPECT_EQ(packet->source(), kGeometryPacketSource);
  const auto& g = packet->geometry();
  EXPECT_EQ(g.field().field_length(), 12000);  // the publisher's field, not the processor's
  EXPECT_EQ(g.field().field_lines_size(), 12);
  ASSERT_EQ(g.calib_size(), 2);
  EXPECT_EQ(g.calib(0).camera_id(), 0u);  // kept, sorted by id
  const auto* c = findCalib(g, 2);
  EXPECT_FLOAT_EQ(c->focal_length(), 1100);
  EXPECT_FLOAT_EQ(c->tx(), float(mine.tx));
  EXPECT_FLOAT_EQ(c->q0(), float(mine.q0));
  EXPECT_NEAR(c->derived_camera_world_tx(), 3000, 0.01);
  EXPECT_EQ(c->pixel_image_width(), 2448u);
  EXPECT_EQ(publisher.stats().malformed, 0u);
  ASSERT_NE(publisher.geometry().camera(2), nullptr);
}

TEST(GeometryPublisher, RepeatedCalibrationDoesNotRepublish) {
  GeometryPublisher publisher(Geometry{FieldModel::divisionB(), {}}, loopbackOptions());
  publisher.start();
  CalibrationSender processor(kLoopback, publisher.listenPort());
  processor.send(FieldModel::divisionB(), {overheadCamera(1, 0)});
  ASSERT_TRUE(stepUntil(publisher, [&] { return publisher.stats().accepted == 1; }));
  const uint64_t after_change = publisher.stats().published;
  EXPECT_EQ(after_change, 2u);  // start + change
  processor.send(FieldModel::divisionB(), {overheadCamera(1, 0)});
  ASSERT_TRUE(stepUntil(publisher, [&] { return publisher.stats().accepted == 2; }));
  EXPECT_EQ(publisher.stats().published, after_change);
}

TEST(GeometryPublisher, MalformedPacketsAreDroppedAndCounted) {
  GeometryPublisher publisher(Geometry{FieldModel::divisionB(), {}}, loopbackOptions());
  publisher.start();
  CalibrationSender processor(kLoopback, publisher.listenPort());
  processor.sendRaw(std::string("\xff\xff\xff\xff garbage", 12));  // not protobuf
  ssl::SSL_WrapperPacket detection_only;
  detection_only.set_source(ssl::SSL_SOURCE_OTHER);
  processor.sendRaw(detection_only.SerializeAsString());  // no geometry
  ASSERT_TRUE(stepUntil(publisher, [&] { return publisher.stats().malformed == 2; }));
  EXPECT_EQ(publisher.stats().datagrams, 2u);
  EXPECT_EQ(publisher.stats().accepted, 0u);
  EXPECT_TRUE(publisher.geometry().cameras.empty());
}

TEST(GeometryPublisher, DropMessagesAreRateLimited) {
  // Capture the log lines of this test only.
  std::ostringstream lines;
  auto previous = spdlog::default_logger();
  spdlog::set_default_logger(std::make_shared<spdlog::logger>(
      "capture", std::make_shared<spdlog::sinks::ostream_sink_mt>(lines)));
  {
    GeometryPublisher publisher(Geometry{FieldModel::divisionB(), {}}, loopbackOptions());
    const uint32_t stranger = inet_addr("10.1.2.3"), friendly = inet_addr(kLoopback);
    for (int i = 0; i < 5; ++i) publisher.handleDatagram("x", 1, stranger);
    for (int i = 0; i < 5; ++i) publisher.handleDatagram("\xff", 1, friendly);
    EXPECT_EQ(publisher.stats().unknown_source, 5u);
    EXPECT_EQ(publisher.stats().malformed, 5u);
  }
  spdlog::set_default_logger(previous);
  const std::string log = lines.str();
  auto count = [&](const std::string& what) {
    size_t n = 0;
    for (size_t at = log.find(what); at != std::string::npos; at = log.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("from 10.1.2.3: not an allowed source"), 1u) << log;
  EXPECT_EQ(count("does not parse as SSL_WrapperPacket"), 1u) << log;
}

TEST(GeometryPublisher, IncompleteCalibrationIsMalformed) {
  GeometryPublisher publisher(Geometry{FieldModel::divisionB(), {}}, loopbackOptions());
  ssl::SSL_WrapperPacket packet;
  auto* calib = packet.mutable_geometry()->add_calib();
  calib->set_camera_id(1);
  calib->set_focal_length(900);  // the other required fields are missing
  const std::string bytes = packet.SerializePartialAsString();
  EXPECT_EQ(publisher.handleDatagram(bytes.data(), bytes.size(), inet_addr(kLoopback)),
            GeometryPublisher::Verdict::Malformed);
  EXPECT_EQ(publisher.stats().malformed, 1u);
}

TEST(GeometryPublisher, UnknownSourceIsDroppedAndCounted) {
  GeometryPublisher publisher(Geometry{FieldModel::divisionB(), {}}, loopbackOptions());
  publisher.start();
  // 127.0.0.2 is loopback too, but not in the allowed list.
  CalibrationSender stranger(kLoopback, publisher.listenPort(), "127.0.0.2");
  ASSERT_TRUE(stranger.send(FieldModel::divisionB(), {overheadCamera(1, 0)}));
  ASSERT_TRUE(stepUntil(publisher, [&] { return publisher.stats().unknown_source == 1; }));
  EXPECT_EQ(publisher.stats().accepted, 0u);
  EXPECT_EQ(publisher.geometry().camera(1), nullptr);
}

TEST(GeometryPublisher, ImplausibleOrOutOfRangeCalibrationsAreRejected) {
  GeometryPublisher publisher(Geometry{FieldModel::divisionB(), {}}, loopbackOptions());
  publisher.start();
  CalibrationSender processor(kLoopback, publisher.listenPort());
  CameraCalibration below = overheadCamera(1, 0);
  below.tz = -below.tz;  // camera under the carpet
  CameraCalibration no_focal = overheadCamera(2, 0);
  no_focal.focal_length = 0;
  processor.send(FieldModel::divisionB(), {below, no_focal});
  processor.send(FieldModel::divisionB(), {overheadCamera(4, 0)});  // --num-cameras 4: ids 0..3
  ASSERT_TRUE(stepUntil(publisher, [&] { return publisher.stats().rejected == 3; }));
  EXPECT_EQ(publisher.stats().accepted, 0u);
  EXPECT_TRUE(publisher.geometry().cameras.empty());
  EXPECT_EQ(publisher.stats().published, 1u);  // only the one from start()
}

// A calibration packet whose q0 has its top mantissa bit flipped on the way.
TEST(GeometryPublisher, NonUnitQuaternionIsRejected) {
  GeometryPublisher publisher(Geometry{FieldModel::divisionB(), {}}, loopbackOptions());
  ssl::SSL_WrapperPacket packet;
  *packet.mutable_geometry()->mutable_field() = toProto(FieldModel::divisionB());
  auto* calib = packet.mutable_geometry()->add_calib();
  *calib = toProto(overheadCamera(1, 0));
  float q = calib->q0();  // 1 for this camera; the flip makes it 1.5
  uint32_t bits;
  std::memcpy(&bits, &q, 4);
  bits ^= 1u << 22;
  std::memcpy(&q, &bits, 4);
  calib->set_q0(q);
  const std::string bytes = packet.SerializeAsString();
  EXPECT_EQ(publisher.handleDatagram(bytes.data(), bytes.size(), inet_addr(kLoopback)),
            GeometryPublisher::Verdict::Rejected);
  EXPECT_EQ(publisher.stats().rejected, 1u);
  EXPECT_EQ(publisher.geometry().camera(1), nullptr);
  // The same calibration intact is taken.
  *calib = toProto(overheadCamera(1, 0));
  const std::string good = packet.SerializeAsString();
  EXPECT_EQ(publisher.handleDatagram(good.data(), good.size(), inet_addr(kLoopback)),
            GeometryPublisher::Verdict::Accepted);
}

TEST(GeometryPublisher, ZeroImageSizeIsRejected) {
  GeometryPublisher publisher(Geometry{FieldModel::divisionB(), {}}, loopbackOptions());
  ssl::SSL_WrapperPacket packet;
  *packet.mutable_geometry()->mutable_field() = toProto(FieldModel::divisionB());
  auto* calib = packet.mutable_geometry()->add_calib();
  *calib = toProto(overheadCamera(1, 0));
  calib->set_pixel_image_width(0);
  const std::string bytes = packet.SerializeAsString();
  EXPECT_EQ(publisher.handleDatagram(bytes.data(), bytes.size(), inet_addr(kLoopback)),
            GeometryPublisher::Verdict::Rejected);
  EXPECT_EQ(publisher.geometry().camera(1), nullptr);
}

TEST(GeometryPublisher, BadOptionsAreInputErrors) {
  auto o = loopbackOptions();
  o.allowed_sources = {"vision-pc"};
  EXPECT_THROW(GeometryPublisher(Geometry{FieldModel::divisionB(), {}}, o), InputError);
  o = loopbackOptions();
  o.interval_s = 0;
  EXPECT_THROW(GeometryPublisher(Geometry{FieldModel::divisionB(), {}}, o), InputError);
  o = loopbackOptions();
  o.num_cameras = 1;  // the field file's camera 2 is outside
  EXPECT_THROW(GeometryPublisher(Geometry{FieldModel::divisionB(), {overheadCamera(2, 0)}}, o), InputError);
}

TEST(GeometryPublisher, ProcessorReceivesFieldAndItsCalibration) {
  auto options = loopbackOptions();
  options.interval_s = 0.05;
  GeometryPublisher publisher(Geometry{FieldModel::divisionA(), {overheadCamera(0, -3000), overheadCamera(3, 3000)}},
                              options);
  std::thread thread([&] { publisher.run(5.0); });
  GeometryReceiveOptions receive;
  receive.group = kGroup;
  receive.port = options.port;
  receive.interface_addr = kLoopback;
  const auto got = receiveGeometry(3, 3.0, receive);
  publisher.stop();
  thread.join();
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->field.field_length, 12000);
  EXPECT_EQ(got->field.lines.size(), 12u);
  ASSERT_EQ(got->cameras.size(), 1u);
  EXPECT_EQ(got->cameras[0].camera_id, 3u);
  EXPECT_NEAR(CameraModel(got->cameras[0]).position().x(), 3000, 0.01);
}

TEST(GeometryPublisher, ReceiveGeometryTimesOut) {
  GeometryReceiveOptions receive;
  receive.group = kGroup;
  receive.port = randomPort();
  receive.interface_addr = kLoopback;
  const auto begin = std::chrono::steady_clock::now();
  EXPECT_FALSE(receiveGeometry(0, 0.2, receive).has_value());
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count(), 2.0);
}

// ---- the CLI ----

int runCli(const std::string& args, std::string* output) {
  const std::string cmd = std::string(DV_CLI_PATH) + " " + args + " 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return -1;
  char buf[4096];
  output->clear();
  while (size_t n = std::fread(buf, 1, sizeof buf, pipe)) output->append(buf, n);
  const int status = ::pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(GeometryCli, PublishesCountPacketsAndStops) {
  const uint16_t port = randomPort();
  MulticastReceiver rx(kGroup, port, kLoopback);
  std::string out;
  const int rc = runCli("geometry --field " + std::string(DV_SOURCE_DIR) +
                            "/config/fields/division_b.json --count 2 --interval 0.05 --listen-port 0 "
                            "--listen-addr 127.0.0.1 --multicast-interface 127.0.0.1 --multicast-port " +
                            std::to_string(port),
                        &out);
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("published 2 packet(s)"), std::string::npos) << out;
  const auto packet = receiveGeometryPacket(rx, [](const ssl::SSL_GeometryData& g) {
    return g.field().field_length() == 9000;
  });
  EXPECT_TRUE(packet.has_value()) << out;
}

TEST(GeometryCli, BadFieldFileExitsTwoWithOneLine) {
  std::string out;
  const int rc = runCli("geometry --field /nonexistent/field.json --count 1", &out);
  EXPECT_EQ(rc, 2) << out;
  EXPECT_NE(out.find("/nonexistent/field.json: cannot open"), std::string::npos) << out;
}

TEST(GeometryCli, BadAllowAddressExitsTwo) {
  std::string out;
  const int rc = runCli("geometry --field " + std::string(DV_SOURCE_DIR) +
                            "/config/fields/division_a.json --count 1 --listen-port 0 --allow vision-pc",
                        &out);
  EXPECT_EQ(rc, 2) << out;
  EXPECT_NE(out.find("--allow \"vision-pc\" is not an IPv4 address"), std::string::npos) << out;
}

}  // namespace
}  // namespace dv

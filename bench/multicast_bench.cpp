// Cost of publishing one camera's detection frame (serialize + sendto) and
// the loopback round trip to a receiver on the same host.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <random>
#include <string>

#include "net/multicast.h"
#include "net/vision_publisher.h"

namespace {

uint16_t benchPort() { return uint16_t(49000 + (std::random_device{}() ^ ::getpid()) % 1000); }

// A busy frame: 1 ball and 11 robots per team.
void fillFrame(dv::ssl::SSL_DetectionFrame& f, uint32_t n) {
  f.set_frame_number(n);
  f.set_t_capture(1.7e9 + n / 72.0);
  f.set_t_sent(1.7e9 + n / 72.0 + 0.004);
  f.set_camera_id(0);
  auto* ball = f.add_balls();
  ball->set_confidence(0.9f);
  ball->set_x(100);
  ball->set_y(200);
  ball->set_pixel_x(1000);
  ball->set_pixel_y(900);
  for (int team = 0; team < 2; ++team) {
    for (int id = 0; id < 11; ++id) {
      auto* r = team ? f.add_robots_blue() : f.add_robots_yellow();
      r->set_confidence(1);
      r->set_robot_id(uint32_t(id));
      r->set_x(float(id * 300 - 1500));
      r->set_y(float(team * 1000 - 500));
      r->set_orientation(0.5f);
      r->set_pixel_x(float(id * 200));
      r->set_pixel_y(float(team * 800));
      r->set_height(140);
    }
  }
}

void BM_PublishDetection(benchmark::State& state) {
  dv::VisionPublisherOptions options;
  options.port = benchPort();
  options.interface_addr = "127.0.0.1";
  dv::VisionPublisher publisher(options);
  uint32_t n = 0;
  for (auto _ : state) {
    fillFrame(publisher.detection(), ++n);
    benchmark::DoNotOptimize(publisher.sendDetection());
  }
  state.counters["send_errors"] = double(publisher.sender().errorCount());
}
BENCHMARK(BM_PublishDetection);

void BM_LoopbackRoundTrip(benchmark::State& state) {
  const uint16_t port = benchPort();
  dv::MulticastReceiver rx("224.5.23.2", port, "127.0.0.1");
  dv::MulticastSender tx("224.5.23.2", port, "127.0.0.1");
  dv::ssl::SSL_WrapperPacket packet;
  fillFrame(*packet.mutable_detection(), 1);
  const std::string bytes = packet.SerializeAsString();
  std::string got;
  int64_t lost = 0;
  for (auto _ : state) {
    tx.send(bytes);
    if (!rx.receive(1.0, got)) ++lost;
  }
  state.counters["bytes_per_packet"] = double(bytes.size());
  state.counters["lost"] = double(lost);
}
BENCHMARK(BM_LoopbackRoundTrip);

}  // namespace

BENCHMARK_MAIN();

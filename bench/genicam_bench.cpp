// The GenICam receive path at full rate: Aravis's fake GigE Vision camera
// streams 2448x2048 BayerRG8 at 60 fps over loopback (GVSP, thousands of UDP
// packets a frame) into GenicamSource for N seconds. Reports frames
// received / skipped (incomplete) / lost (never delivered), the CPU time of
// the receive path (Aravis's stream thread + the grabbing thread, per
// second of wall time), arrival jitter against the 60 fps period, and how
// far the mapped capture time lies before the arrival. The fake camera
// sends from a thread of this same process, so on a small machine it
// competes with the receiver (other_cpu_%).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <dirent.h>
#include <fstream>
#include <sstream>
#include <vector>

#include "../tests/fake_gige_camera.h"
#include "camera/genicam_source.h"

namespace {

// CPU seconds (user + system) of this process's threads whose name starts
// with `prefix` ("" = all), from /proc/self/task/*/stat.
double threadCpuSeconds(const std::string& prefix) {
  double total = 0;
  const double tick = static_cast<double>(::sysconf(_SC_CLK_TCK));
  DIR* d = ::opendir("/proc/self/task");
  if (!d) return -1;
  while (dirent* e = ::readdir(d)) {
    if (e->d_name[0] == '.') continue;
    const std::string dir = std::string("/proc/self/task/") + e->d_name;
    std::string comm;
    std::getline(std::ifstream(dir + "/comm") >> std::ws, comm);
    if (comm.rfind(prefix, 0) != 0) continue;
    std::string stat;
    std::getline(std::ifstream(dir + "/stat"), stat);
    std::istringstream rest(stat.substr(stat.rfind(')') + 2));  // after "pid (comm) "
    std::string field;
    double utime = 0, stime = 0;
    for (int i = 3; i <= 15 && rest >> field; ++i) {
      if (i == 14) utime = std::stod(field);
      if (i == 15) stime = std::stod(field);
    }
    total += (utime + stime) / tick;
  }
  ::closedir(d);
  return total;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

void BM_GenicamStream2448At60(benchmark::State& state) {
  const double seconds = static_cast<double>(state.range(0));
  dv::test::FakeGigeCamera cam("DVbench" + std::to_string(::getpid() % 10000), 2448, 2048, true);
  if (!cam.running()) {
    state.SkipWithError("the fake GigE camera cannot listen on 127.0.0.1:3956");
    return;
  }
  dv::GenicamSource src(cam.deviceId());
  std::vector<dv::CameraSetting> settings = {
      {"Width", "2448"}, {"Height", "2048"}, {"PixelFormat", "BayerRG8"}, {"AcquisitionFrameRate", "60"}};
  // Second argument: GVSP packet size (0: as negotiated, 1400 on this link; 8000: jumbo-like).
  if (state.range(1) > 0) settings.push_back({"ArvGevSCPSPacketSize", std::to_string(state.range(1))});
  src.applySettings(settings);
  for (auto _ : state) {
    dv::Frame f;
    std::string why;
    // Warm-up: the stream is open and a first frame has arrived.
    for (dv::GrabStatus s = dv::GrabStatus::Timeout; s != dv::GrabStatus::Frame;) {
      s = src.grab(f, 2.0, why);
      if (s == dv::GrabStatus::Lost) return state.SkipWithError(why.c_str());
    }
    const dv::SourceCounters before = src.counters();
    const double stream_cpu0 = threadCpuSeconds("arv_gv_stream");
    const double process_cpu0 = threadCpuSeconds("");
    timespec grab0{};
    ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &grab0);
    std::vector<double> interval_error, behind;
    double previous_arrival = f.t_arrival;
    uint64_t skipped = 0, lost_events = 0;
    const auto start = std::chrono::steady_clock::now();
    const auto end = start + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      const dv::GrabStatus s = src.grab(f, 1.0, why);
      if (s == dv::GrabStatus::Frame) {
        interval_error.push_back(std::fabs(f.t_arrival - previous_arrival - 1.0 / 60));
        behind.push_back(f.t_arrival - f.t_capture);
        previous_arrival = f.t_arrival;
      } else if (s == dv::GrabStatus::Skipped) {
        ++skipped;
      } else if (s == dv::GrabStatus::Lost) {
        ++lost_events;
        if (!src.reconnect(why)) break;
      }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    timespec grab1{};
    ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &grab1);
    const double grab_cpu = (grab1.tv_sec - grab0.tv_sec) + 1e-9 * (grab1.tv_nsec - grab0.tv_nsec);
    const double stream_cpu = threadCpuSeconds("arv_gv_stream") - stream_cpu0;
    const dv::SourceCounters after = src.counters();
    state.SetIterationTime(wall);
    state.counters["frames"] = static_cast<double>(after.frames - before.frames);
    state.counters["skipped"] = static_cast<double>(skipped);
    state.counters["lost_frames"] = static_cast<double>(after.lost_frames - before.lost_frames);
    state.counters["camera_lost"] = static_cast<double>(lost_events);
    state.counters["fps"] = static_cast<double>(after.frames - before.frames) / wall;
    state.counters["recv_cpu_%"] = 100 * (stream_cpu + grab_cpu) / wall;
    state.counters["grab_cpu_%"] = 100 * grab_cpu / wall;
    // The rest of the process is mostly the fake camera's sending thread.
    state.counters["other_cpu_%"] = 100 * (threadCpuSeconds("") - process_cpu0 - stream_cpu - grab_cpu) / wall;
    state.counters["jitter_p50_ms"] = 1e3 * percentile(interval_error, 0.5);
    state.counters["jitter_p99_ms"] = 1e3 * percentile(interval_error, 0.99);
    state.counters["behind_p99_ms"] = 1e3 * percentile(behind, 0.99);
  }
}
BENCHMARK(BM_GenicamStream2448At60)
    ->Args({10, 0})
    ->Args({10, 8000})
    ->Args({60, 0})
    ->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();

// Throughput of writing and reading SSL log files, plain and gzip, with
// records the size of a typical detection wrapper (about 300 bytes).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "io/ssl_log.h"

namespace {

constexpr int kRecords = 20000;
constexpr size_t kPayloadBytes = 300;

std::string benchPath(const char* suffix) {
  return (std::filesystem::temp_directory_path() /
          ("dv_ssl_log_bench_" + std::to_string(::getpid()) + suffix))
      .string();
}

std::string payload() {
  std::string p(kPayloadBytes, '\0');
  uint32_t x = 1;
  // Protobuf-like bytes: partly repetitive, partly noise.
  for (size_t i = 0; i < p.size(); ++i) p[i] = char(i % 4 ? (x = x * 1664525u + 1013904223u) >> 24 : i);
  return p;
}

void writeLog(const std::string& path) {
  const std::string p = payload();
  dv::SslLogWriter w(path);
  for (int i = 0; i < kRecords; ++i) w.write(int64_t(i) * 13'888'889, dv::LogMessageType::Vision2014, p);
  w.close();
}

void BM_Write(benchmark::State& state, const char* suffix) {
  const std::string path = benchPath(suffix);
  for (auto _ : state) writeLog(path);
  state.SetItemsProcessed(state.iterations() * kRecords);
  state.SetBytesProcessed(state.iterations() * kRecords * int64_t(kPayloadBytes + 16));
  std::filesystem::remove(path);
}

void BM_Read(benchmark::State& state, const char* suffix) {
  const std::string path = benchPath(suffix);
  writeLog(path);
  dv::LogRecord record;
  for (auto _ : state) {
    dv::SslLogReader reader(path);
    int n = 0;
    while (reader.next(record)) ++n;
    benchmark::DoNotOptimize(n);
  }
  state.SetItemsProcessed(state.iterations() * kRecords);
  state.SetBytesProcessed(state.iterations() * kRecords * int64_t(kPayloadBytes + 16));
  std::filesystem::remove(path);
}

BENCHMARK_CAPTURE(BM_Write, plain, ".log")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Write, gzip, ".log.gz")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Read, plain, ".log")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Read, gzip, ".log.gz")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

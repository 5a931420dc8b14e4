#include "camera/receive_buffer.h"

#include <algorithm>
#include <fstream>

namespace dv {

long readRmemMax() {
  std::ifstream in("/proc/sys/net/core/rmem_max");
  long v = -1;
  if (!(in >> v)) return -1;
  return v;
}

size_t streamSocketBufferBytes(size_t payload) {
  constexpr size_t kMin = size_t(2) << 20, kMax = size_t(256) << 20;
  return std::clamp(4 * payload, kMin, kMax);
}

std::string rmemCapMessage(const std::string& source, size_t requested, long rmem_max) {
  if (rmem_max < 0 || static_cast<size_t>(rmem_max) >= requested) return {};
  return source + ": the system caps socket receive buffers at " + std::to_string(rmem_max) +
         " bytes (net.core.rmem_max), less than the " + std::to_string(requested) +
         " asked for the GigE stream; frames may lose packets at full rate. Remedy (as root): "
         "sysctl -w net.core.rmem_max=" + std::to_string(requested);
}

}  // namespace dv

#pragma once
// The two clocks the live code uses, in seconds: Unix time (what packets
// carry) and a monotonic clock (for waits and rates, immune to clock steps).
#include <chrono>

namespace dv {

inline double unixSeconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}
inline double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace dv

#pragma once
// A small, fully specified random generator (SplitMix64), so that scenes and
// noise are the same for a seed on every platform and standard library.
#include <cmath>
#include <cstdint>

namespace dv {

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}

  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1).
  double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [0, n).
  int below(int n) { return int(uniform() * n); }
  // Standard normal (Box-Muller).
  double normal() {
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2 * 3.14159265358979323846 * u2);
  }

 private:
  uint64_t state_;
};

// Mixes several values into one seed, so (scene seed, frame, camera) streams
// do not overlap.
inline uint64_t mixSeed(uint64_t a, uint64_t b, uint64_t c = 0) {
  SplitMix64 m(a ^ (b * 0xD6E8FEB86659FD93ull) ^ (c * 0xA0761D6478BD642Full));
  m.next();
  return m.next();
}

}  // namespace dv

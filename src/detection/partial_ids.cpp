#include "detection/partial_ids.h"

namespace dv {

void resolvePartialIds(std::vector<Hypothesis>& robots) {
  for (auto& r : robots) {
    r.id_known = r.fullPattern();
    if (r.fullPattern()) continue;
    int missing[4], m = 0;
    for (int s = 0; s < 4; ++s)
      if (!(r.seen_sides >> s & 1)) missing[m++] = s;
    auto taken = [&](int id) {
      for (const auto& o : robots)
        if (&o != &r && o.fullPattern() && o.team == r.team && o.id == id) return true;
      return false;
    };
    int free = 0;
    std::array<MarkerColor, 4> guess = r.colors;
    for (int flips = 0; flips < (1 << m); ++flips) {
      auto c = r.colors;
      for (int i = 0; i < m; ++i) {
        MarkerColor& side = c[missing[i]];
        if (flips >> i & 1) side = side == MarkerColor::Green ? MarkerColor::Pink : MarkerColor::Green;
      }
      if (taken(patternId(c))) continue;
      if (free++ == 0) guess = c;
    }
    r.colors = guess;
    r.id = patternId(guess);
    r.id_known = free == 1;
  }
}

}  // namespace dv

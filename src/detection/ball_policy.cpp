#include "detection/ball_policy.h"

#include <algorithm>
#include <cmath>

namespace dv {

void selectBalls(std::vector<BallCandidate>& cands, double ball_radius, int max_balls) {
  std::sort(cands.begin(), cands.end(), [](const BallCandidate& a, const BallCandidate& b) {
    return a.confidence != b.confidence ? a.confidence > b.confidence : a.rank > b.rank;
  });
  const double same = kSameBallRadii * ball_radius;
  int kept = 0;
  for (size_t i = 0; i < cands.size(); ++i) {
    bool dup = false;
    for (int j = 0; j < kept && !dup; ++j)
      dup = std::hypot(cands[i].pos.x - cands[j].pos.x, cands[i].pos.y - cands[j].pos.y) < same;
    if (!dup && kept < max_balls) cands[kept++] = cands[i];
  }
  cands.resize(kept);
  bool round_ball = false;
  for (const auto& c : cands) round_ball |= !c.streak;
  if (round_ball)
    cands.erase(std::remove_if(cands.begin(), cands.end(), [](const BallCandidate& c) { return c.streak && c.track < 0; }),
                cands.end());
}

}  // namespace dv

// The fast-ball pass's coarse rows (streak_score.h): the vector path (pair
// sums, interleaved, streamed out) against the plain means, for coarse rows
// that start at every alignment and widths that leave a remainder.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "pipeline/streak_score.h"

namespace dv {
namespace {

TEST(PipelineStreakCoarse, RowsAreThePlainMeansOfTheFirstGridRow) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> value(-3.0f, 3.0f);
  for (double scale : {5.6, 3.7}) {  // factor 2 and factor 3
    for (int width : {61, 64, 203}) {
      const int height = 14;
      const StreakWindows w = streakWindows(scale, width, height);
      std::vector<float> ca(static_cast<size_t>(width) * height), cb(ca.size());
      for (auto& v : ca) v = value(rng);
      for (auto& v : cb) v = value(rng);
      std::vector<float> coarse(2 * static_cast<size_t>(w.coarse_width) * w.coarse_height, -99.0f);
      streakCoarseRows(ca.data(), cb.data(), width, w, coarse.data(), 0, w.coarse_height);
      const float norm = 1.0f / static_cast<float>(w.factor);
      long wrong = 0;
      for (int cy = 0; cy < w.coarse_height; ++cy)
        for (int cx = 0; cx < w.coarse_width; ++cx) {
          float sa = 0, sb = 0;
          for (int i = 0; i < w.factor; ++i) {
            sa += ca[static_cast<size_t>(cy) * w.factor * width + cx * w.factor + i];
            sb += cb[static_cast<size_t>(cy) * w.factor * width + cx * w.factor + i];
          }
          const size_t k = 2 * (static_cast<size_t>(cy) * w.coarse_width + cx);
          wrong += coarse[k] != sa * norm || coarse[k + 1] != sb * norm;
        }
      EXPECT_EQ(wrong, 0) << "scale " << scale << " width " << width << " factor " << w.factor;
    }
  }
}

}  // namespace
}  // namespace dv

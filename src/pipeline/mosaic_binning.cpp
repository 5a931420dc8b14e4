#include "pipeline/mosaic_binning.h"

#include <cstdint>

#include "pipeline/bayer_subsample.h"

namespace dv {

void binMosaicRows(const cv::Mat& raw, BayerPattern pattern, cv::Mat& out, int cell_begin, int cell_end) {
  const BayerSites s = bayerSites(pattern);
  const int cells = raw.cols / 4;
  for (int j = cell_begin; j < cell_end; ++j) {
    const uint8_t* r[4];
    for (int k = 0; k < 4; ++k) r[k] = raw.ptr<uint8_t>(4 * j + k);
    uint8_t* o[2] = {out.ptr<uint8_t>(2 * j), out.ptr<uint8_t>(2 * j + 1)};
    for (int i = 0; i < cells; ++i) {
      // Sums of the four pixels of each site of the 2x2 pattern in the block.
      int sum[2][2];
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) {
          const int c = 4 * i + x;
          sum[y][x] = r[y][c] + r[y][c + 2] + r[y + 2][c] + r[y + 2][c + 2];
        }
      const int red = sum[s.ry][s.rx], blue = sum[s.by][s.bx];
      const int green = sum[0][0] + sum[0][1] + sum[1][0] + sum[1][1] - red - blue;
      const uint8_t g = static_cast<uint8_t>((green + 4) >> 3);
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) o[y][2 * i + x] = g;
      o[s.ry][2 * i + s.rx] = static_cast<uint8_t>((red + 2) >> 2);
      o[s.by][2 * i + s.bx] = static_cast<uint8_t>((blue + 2) >> 2);
    }
  }
}

}  // namespace dv

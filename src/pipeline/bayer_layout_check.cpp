#include "pipeline/bayer_layout_check.h"

#include <cstdio>

namespace dv {

std::string bayerLayoutWarning(const cv::Mat& raw, BayerPattern pattern) {
  if (pattern == BayerPattern::None || raw.empty() || raw.type() != CV_8UC1 || raw.rows < 2 ||
      raw.cols < 2)
    return {};
  // Mean of each site of the 2x2 cell over a sparse lattice of cells.
  double sum[2][2] = {{0, 0}, {0, 0}};
  long n = 0;
  for (int y = 0; y + 1 < raw.rows; y += 16) {
    const uint8_t* r0 = raw.ptr<uint8_t>(y);
    const uint8_t* r1 = raw.ptr<uint8_t>(y + 1);
    for (int x = 0; x + 1 < raw.cols; x += 16) {
      sum[0][0] += r0[x], sum[0][1] += r0[x + 1], sum[1][0] += r1[x], sum[1][1] += r1[x + 1];
      ++n;
    }
  }
  if (n == 0) return {};
  const double main_diag = (sum[0][0] + sum[1][1]) / (2.0 * n);
  const double anti_diag = (sum[0][1] + sum[1][0]) / (2.0 * n);
  // RGGB and BGGR have green on the anti-diagonal, GRBG and GBRG on the main one.
  const bool green_anti = pattern == BayerPattern::RGGB || pattern == BayerPattern::BGGR;
  const double green = green_anti ? anti_diag : main_diag;
  const double other = green_anti ? main_diag : anti_diag;
  // Too dark to judge, or not clearly darker: say nothing.
  if (other < 16 || green >= 0.8 * other) return {};
  char text[256];
  std::snprintf(text, sizeof text,
                "the sites Bayer layout %s takes as green are darker than the other diagonal "
                "(mean %.0f vs %.0f); the layout is probably %s (set it with --bayer)",
                bayerPatternName(pattern), green, other, green_anti ? "grbg or gbrg" : "rggb or bggr");
  return text;
}

}  // namespace dv

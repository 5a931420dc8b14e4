// Packed chroma from the Bayer mosaic: the vectorised rows (16 samples a
// step, the last step overlapping the one before it) against a sample-by-
// sample reference (sampleRgbAt, packChroma), for column ranges of every
// length around the step, at the image borders and for the four layouts.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "pipeline/bayer_subsample.h"

namespace dv {
namespace {

uint32_t referenceSample(const cv::Mat& raw, BayerPattern p, const ChromaFixed& k, int i, int j) {
  float rgb[3];
  sampleRgbAt(raw, p, i, j, rgb);
  return packChroma(k, static_cast<int>(rgb[0]), static_cast<int>(rgb[1]), static_cast<int>(rgb[2]));
}

TEST(PipelineChroma, VectorRowsMatchTheSampleBySampleReference) {
  std::mt19937 rng(3);
  const int ws = 75, hs = 9;  // 75 samples: runs of every length up to the row
  cv::Mat raw(2 * hs, 2 * ws, CV_8UC1);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int y = 0; y < raw.rows; ++y)
    for (int x = 0; x < raw.cols; ++x) raw.at<uint8_t>(y, x) = static_cast<uint8_t>(byte(rng));
  // dRGB-like coefficients in 1/1024 (both signs).
  const ChromaFixed k{{1086, -1086, 0}, {627, 627, -1254}};
  for (BayerPattern p : {BayerPattern::RGGB, BayerPattern::GRBG, BayerPattern::GBRG, BayerPattern::BGGR}) {
    for (int c0 : {0, 1, 5, 17}) {
      for (int c1 = c0 + 1; c1 <= ws; ++c1) {
        std::vector<uint32_t> packed(static_cast<size_t>(ws) * hs, 0xdeadbeefu);
        bayerChromaRows(raw, p, k, packed.data(), 0, hs, c0, c1);
        long wrong = 0, outside = 0;
        for (int j = 0; j < hs; ++j)
          for (int i = 0; i < ws; ++i) {
            const uint32_t v = packed[static_cast<size_t>(j) * ws + i];
            if (i >= c0 && i < c1) wrong += v != referenceSample(raw, p, k, i, j);
            else outside += v != 0xdeadbeefu;
          }
        ASSERT_EQ(wrong, 0) << "pattern " << static_cast<int>(p) << " columns " << c0 << ".." << c1;
        ASSERT_EQ(outside, 0) << "wrote outside columns " << c0 << ".." << c1;
      }
    }
  }
}

}  // namespace
}  // namespace dv

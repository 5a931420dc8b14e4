// The Bayer layout check: silent for the right layout (and for gray scenes),
// a warning naming the likely layouts for a wrong one.
#include <gtest/gtest.h>

#include "pipeline/bayer_layout_check.h"
#include "pipeline_test_scene.h"

namespace dv {
namespace {

constexpr BayerPattern kPatterns[] = {BayerPattern::RGGB, BayerPattern::GRBG, BayerPattern::GBRG,
                                      BayerPattern::BGGR};

bool greenOnAntiDiagonal(BayerPattern p) { return p == BayerPattern::RGGB || p == BayerPattern::BGGR; }

TEST(BayerLayoutCheck, WarnsOnlyWhenTheGreenSitesAreOnTheOtherDiagonal) {
  const auto cam = test::topDownCamera(1000, 500, 150 + 2500, 900, 640, 480);
  test::PaintedScene scene;  // green carpet with a few colored discs
  scene.discs.push_back({{900, 450}, 25, test::kOrange});
  scene.discs.push_back({{1100, 600}, 25, test::kPink});
  scene.noise_sigma = 2;
  for (BayerPattern rendered : kPatterns) {
    const cv::Mat raw = scene.render(cam, rendered);
    for (BayerPattern given : kPatterns) {
      const std::string w = bayerLayoutWarning(raw, given);
      SCOPED_TRACE(std::string("rendered ") + bayerPatternName(rendered) + ", given " + bayerPatternName(given));
      if (greenOnAntiDiagonal(rendered) == greenOnAntiDiagonal(given)) {
        EXPECT_TRUE(w.empty()) << w;
      } else {
        ASSERT_FALSE(w.empty());
        EXPECT_NE(w.find(bayerPatternName(given)), std::string::npos) << w;
        EXPECT_NE(w.find(bayerPatternName(rendered)), std::string::npos) << w;
      }
    }
  }
}

TEST(BayerLayoutCheck, GrayOrDarkOrBgrFramesSayNothing) {
  const auto cam = test::topDownCamera(1000, 500, 150 + 2500, 900, 640, 480);
  test::PaintedScene gray;
  gray.carpet = {90, 90, 90};
  EXPECT_TRUE(bayerLayoutWarning(gray.render(cam, BayerPattern::GRBG), BayerPattern::RGGB).empty());
  test::PaintedScene dark;
  dark.gain = 0.05;
  EXPECT_TRUE(bayerLayoutWarning(dark.render(cam, BayerPattern::GRBG), BayerPattern::RGGB).empty());
  const cv::Mat bgr(480, 640, CV_8UC3, cv::Scalar(50, 110, 40));
  EXPECT_TRUE(bayerLayoutWarning(bgr, BayerPattern::RGGB).empty());
  EXPECT_TRUE(bayerLayoutWarning(cv::Mat(), BayerPattern::RGGB).empty());
}

}  // namespace
}  // namespace dv

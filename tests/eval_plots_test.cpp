// `eval --plot` (eval/eval_plots.h): the histograms and the field map are
// written, and a miss is drawn where it happened, in its kind's color.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "eval/eval_plots.h"
#include "temp_dir.h"

namespace dv {
namespace {

TEST(EvalPlots, HistogramsAndAFieldMapWithTheMissesWhereTheyHappened) {
  TempDir dir("dv_eval_plots");
  Metrics m;
  m.robot_position_errors_mm = {0.3, 0.5, 0.4, 1.2};
  m.robot_orientation_errors_rad = {0.001, 0.004};
  m.misses.push_back({Miss::RobotMissed, -3000, 1500});  // Division B
  m.misses.push_back({Miss::BallMissed, 2000, -1000});
  const auto files = writeEvalPlots((dir.path() / "plots").string(), m);
  // No ball errors: no ball histogram.
  ASSERT_EQ(files.size(), 3u);
  for (const auto& f : files) EXPECT_FALSE(cv::imread(f).empty()) << f;
  const cv::Mat map = cv::imread(files.back());
  ASSERT_FALSE(map.empty());
  // The map spans the Division B field with boundary plus 400 mm margins
  // (-5200..5200 mm across 1200 px): the missed robot's ring is red, the
  // missed ball's disc orange.
  const double scale = 1200.0 / 10400, y_top = 3700;
  auto at = [&](double x, double y) {
    return map.at<cv::Vec3b>(static_cast<int>((y_top - y) * scale), static_cast<int>((x + 5200) * scale));
  };
  const cv::Vec3b ring = at(-3000 + 90, 1500);
  EXPECT_GT(ring[2], 180);
  EXPECT_LT(ring[1], 100);
  const cv::Vec3b ball = at(2000, -1000);
  EXPECT_GT(ball[2], 200);
  EXPECT_GT(ball[1], 100);
  EXPECT_LT(ball[0], 60);
}

TEST(EvalPlots, AFolderThatCannotBeMadeIsNamed) {
  try {
    writeEvalPlots("/proc/no_such_folder/plots", Metrics{});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/no_such_folder/plots"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dv

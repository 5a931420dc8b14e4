// Lens terms from the lines (issue 19, item 4): on a rendered Brown-Conrady
// lens the calibration takes k2..p2 and places the field far better than
// the league's model can; on lenses the league's model fits it stays that
// model (the information test); the report gives both residuals and what
// packets will carry.
#include <gtest/gtest.h>

#include "geometry/calibration/calibrate_camera.h"
#include "geometry/calibration/calibration_report.h"
#include "geometry/calibration/league_fit.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv {
namespace {

struct LensRun {
  CalibrationOutcome out;
  CameraCalibration truth;
  SceneSpec spec;
};

LensRun calibrateRendered(const CameraCalibration& cam, uint64_t seed) {
  LensRun r;
  r.spec.field = FieldModel::divisionB();
  r.spec.seed = seed;
  r.spec.cameras.push_back({cam});
  r.spec.robots = placeRandomRobots(r.spec, 0, 4, 4, seed);
  r.truth = cam;
  const FieldRect reg = *r.spec.field.cameraRegion(0, 2);
  const CameraModel truth(cam);
  CalibrationRequest req;
  req.camera_height_mm = truth.position().z();  // given, as a view from straight above needs
  for (const auto& p : regionCornersCounterClockwise(reg.x_min, reg.x_max, reg.y_min, reg.y_max))
    req.points.push_back({p, *truth.fieldToImage(p)});
  r.out = calibrateCamera(Renderer(r.spec).render(0, 0).image, r.spec.field, req);
  return r;
}

double fieldError(const LensRun& r, const CameraCalibration& c) {
  const FieldRect area = r.spec.field.withBoundary();
  return std::max(meanFieldPositionError(r.truth, c, 0, area, 24), meanFieldPositionError(r.truth, c, 150, area, 24));
}

// 5 m over a Division B half, looking straight down; focal 1300 px is a
// wide-angle lens there (the whole half and its walls in view).
CameraCalibration topDown(double k, const LensTerms& lens, double focal = 1300) {
  CameraCalibration c = makeCamera(0, {-2250, 0, 5000}, {-2250, 0, 0}, focal, k, {6.5, -4}, 2448, 2048, {-1, 0, 0}).calib;
  c.lens = lens;
  return c;
}

TEST(CalibrationLens, BrownConradyLensTakesTheTerms) {
  const LensRun r = calibrateRendered(topDown(0.026, {-0.004, 0, 0.0006, -0.0004}), 7);
  ASSERT_FALSE(r.out.problem) << *r.out.problem;
  ASSERT_TRUE(r.out.lens.has_value());
  EXPECT_TRUE(r.out.lens->lens_used);
  const double with_terms = fieldError(r, r.out.calibration);
  const LeagueFit published = leagueFit(r.out.calibration);
  const double league = fieldError(r, published.calibration);
  std::printf("[ Brown-Conrady lens from lines ] field error %.3f mm with terms, %.3f mm league fit; line rms %.3f px "
              "league, %.3f px with terms; gain %.0f; k2 %.5f (true -0.004) p1 %.5f p2 %.5f\n",
              with_terms, league, r.out.lens->league_rms_px, r.out.lens->lens_rms_px, r.out.lens->information_gain,
              r.out.calibration.lens.k2, r.out.calibration.lens.p1, r.out.calibration.lens.p2);
  EXPECT_LE(with_terms, 1.0);
  EXPECT_GT(league, 2 * with_terms);
  // The report gives both residuals and the published fit.
  const CalibrationReport rep = makeCalibrationReport(r.out, r.spec.field, "frame", 0, 0);
  const std::string text = formatReport(rep);
  EXPECT_NE(text.find("terms beyond the league's model taken"), std::string::npos) << text;
  EXPECT_NE(text.find("published (league model's best fit)"), std::string::npos) << text;
  const auto j = reportToJson(rep);
  EXPECT_TRUE(j["lens"]["terms_used"].get<bool>());
  EXPECT_LT(j["lens"]["line_rms_px"]["lens"].get<double>(), j["lens"]["line_rms_px"]["league"].get<double>());
  EXPECT_GT(j["published"]["field_error_mm"]["mean"].get<double>(), 0.3);
}

TEST(CalibrationLens, LeagueLensesStayTheLeagueModel) {
  const CameraCalibration tilted =
      makeCamera(0, {-2000, -3800, 4200}, {-2300, -300, 0}, 1100, 0.12, {10, -6}, 2448, 2048).calib;
  for (const CameraCalibration& cam : {topDown(0.03, {}), topDown(-0.02, {}), topDown(0.03, {}, 1750), tilted}) {
    const LensRun r = calibrateRendered(cam, 3);
    ASSERT_FALSE(r.out.problem) << *r.out.problem;
    ASSERT_TRUE(r.out.lens.has_value());
    std::printf("[ league lens k %.2f ] information gain %.1f, line rms %.3f px, %.3f px with terms\n", cam.distortion,
                r.out.lens->information_gain, r.out.lens->league_rms_px, r.out.lens->lens_rms_px);
    EXPECT_FALSE(r.out.lens->lens_used);
    EXPECT_FALSE(r.out.calibration.lens.any());
  }
}

}  // namespace
}  // namespace dv

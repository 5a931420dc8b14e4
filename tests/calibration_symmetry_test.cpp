// The field's half-turn symmetry: every pose has a twin that sees the same
// lines; which one is taken is decided by a target (layout, hint) and said,
// and a view that looks the same both ways is not decided.
#include <gtest/gtest.h>

#include "geometry/calibration/field_symmetry.h"
#include "geometry/calibration/view_hint.h"
#include "core/error.h"
#include "synth/scene.h"

namespace dv {
namespace {

CameraParams tiltedAt(FieldPoint position, FieldPoint look_at) {
  return CameraParams::fromCalibration(makeCamera(0, position, look_at, 900, 0.05, {0, 0}, 1224, 1024).calib);
}

TEST(CalibrationSymmetry, TwinSeesTheTurnedFieldInTheSamePixels) {
  const CameraParams p = tiltedAt({-2000, -2500, 4000}, {-2500, 500, 0});
  const CameraModel a(p.toCalibration(0, 1224, 1024)), b(halfTurnTwin(p).toCalibration(0, 1224, 1024));
  for (const FieldPoint q : {FieldPoint{-2500, 500, 0}, FieldPoint{-4500, 1000, 0}, FieldPoint{-1000, 0, 150}}) {
    const auto pa = a.fieldToImage(q), pb = b.fieldToImage({-q.x, -q.y, q.z});
    ASSERT_TRUE(pa && pb);
    EXPECT_NEAR(pa->u, pb->u, 1e-6);
    EXPECT_NEAR(pa->v, pb->v, 1e-6);
  }
}

TEST(CalibrationSymmetry, TargetPicksTheReadingAndNamesTheAlternative) {
  const CameraParams p = tiltedAt({-2000, -2500, 4000}, {-2500, 500, 0});
  // Found looking at x<0; the operator says the camera looks at x>0.
  const SymmetryChoice c = chooseNearTarget(p, {2250, 0}, "--region x>0", 1224, 1024);
  EXPECT_TRUE(c.decision.decided);
  EXPECT_NEAR(c.params.position[0], 2000, 1e-6);
  EXPECT_NEAR(c.decision.view.x, 2500, 1);
  EXPECT_NEAR(c.decision.alternative_view.x, -2500, 1);
  const std::string line = c.decision.describe();
  EXPECT_NE(line.find("settled by --region x>0"), std::string::npos) << line;
  EXPECT_NE(line.find("alternative"), std::string::npos) << line;
  EXPECT_NE(line.find("--near -2500,500"), std::string::npos) << line;
  const SymmetryChoice same = chooseNearTarget(p, {-2250, 0}, "the layout", 1224, 1024);
  EXPECT_NEAR(same.params.position[0], -2000, 1e-6);
}

TEST(CalibrationSymmetry, ViewOfTheCenterIsNotDecided) {
  const CameraParams p = tiltedAt({0, -2500, 4000}, {0, 100, 0});
  const SymmetryChoice c = chooseNearTarget(p, {-2250, 0}, "the camera-id layout", 1224, 1024);
  EXPECT_FALSE(c.decision.decided);
  EXPECT_NE(c.decision.describe().find("NOT settled"), std::string::npos) << c.decision.describe();
  // A target on the line between the two readings decides nothing either.
  const CameraParams q = tiltedAt({-2000, 0, 4000}, {-2500, 0, 0});
  EXPECT_FALSE(chooseNearTarget(q, {0, 2000}, "--near 0,2000", 1224, 1024).decision.decided);
}

TEST(CalibrationSymmetry, HintsParseAndBadOnesNameTheOption) {
  const FieldModel f = FieldModel::divisionB();
  const ViewHint r = parseRegionHint("x>0,y<0", f, "command line");
  EXPECT_EQ(r.region.x_min, 0);
  EXPECT_EQ(r.region.x_max, 4500);
  EXPECT_EQ(r.region.y_max, 0);
  EXPECT_EQ(parseRegionHint("center", f, "command line").region.x_max, 2250);
  const ViewHint n = parseNearHint("2000,-1500", f, "command line");
  EXPECT_EQ(n.near.x, 2000);
  EXPECT_EQ(n.near.y, -1500);
  for (const char* bad : {"x>1", "y<0", "x<0,x>0", ""}) {
    try {
      parseRegionHint(bad, f, "command line");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--region"), std::string::npos) << e.what();
    }
  }
  for (const char* bad : {"2000", "a,b", "1,2,3", "9000,0"}) EXPECT_THROW(parseNearHint(bad, f, "command line"), InputError) << bad;
}

}  // namespace
}  // namespace dv

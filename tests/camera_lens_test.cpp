// Camera model with Brown-Conrady lens terms (LensTerms): the league's model
// when they are zero, the stated polynomial, exact inverses both ways, and no
// answer past the fold of the lens.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/camera_model.h"
#include "synth/scene.h"

namespace dv {
namespace {

// A tilted 2448 x 2048 camera with the wide-angle lens.
CameraCalibration wideLens() {
  CameraCalibration c = makeCamera(0, {-2000, -2500, 4500}, {-2500, 300, 0}, 1300, 0.026, {8, -5}, 2448, 2048).calib;
  c.lens = {-0.004, 0.0004, 0.0006, -0.0004};
  return c;
}

TEST(CameraLens, ZeroTermsAreTheLeagueModelBitForBit) {
  const double zero[4] = {0, 0, 0, 0};
  for (double k : {-0.2, 0.0, 0.03, 0.25})
    for (double x = -1.3; x <= 1.3; x += 0.137)
      for (double y = -1.1; y <= 1.1; y += 0.123) {
        double ux, uy;
        const double s = undistortNormalised(x, y, k, zero, &ux, &uy);
        const double league = 1 + k * (x * x + y * y);
        EXPECT_EQ(s, league);
        EXPECT_EQ(ux, x * league);
        EXPECT_EQ(uy, y * league);
      }
}

TEST(CameraLens, FollowsThePolynomialFromDistortedToUndistorted) {
  CameraCalibration c;
  c.focal_length = 1000, c.principal_point_x = 1000, c.principal_point_y = 800;
  c.distortion = 0.02;
  c.lens = {-0.005, 0.001, 0.002, -0.003};
  const CameraModel m(c);
  double nx, ny;
  // Pixel (1300, 1000): d = (0.3, 0.2), r^2 = 0.13.
  m.undistortPixel({1300, 1000}, &nx, &ny);
  const double r2 = 0.13, s = 1 + 0.02 * r2 - 0.005 * r2 * r2 + 0.001 * r2 * r2 * r2;
  EXPECT_NEAR(nx, 0.3 * s + 2 * 0.002 * 0.3 * 0.2 - 0.003 * (r2 + 2 * 0.09), 1e-15);
  EXPECT_NEAR(ny, 0.2 * s + 0.002 * (r2 + 2 * 0.04) + 2 * -0.003 * 0.3 * 0.2, 1e-15);
}

TEST(CameraLens, BothDirectionsAreInverses) {
  const CameraModel m(wideLens());
  int n = 0;
  for (double v = 0; v <= 2047; v += 97)
    for (double u = 0; u <= 2447; u += 101) {
      for (double z : {0.0, 150.0}) {
        const auto p = m.imageToField({u, v}, z);
        ASSERT_TRUE(p.has_value()) << u << "," << v;
        const auto back = m.fieldToImage(*p);
        ASSERT_TRUE(back.has_value());
        EXPECT_NEAR(back->u, u, 1e-6);
        EXPECT_NEAR(back->v, v, 1e-6);
        ++n;
      }
    }
  EXPECT_GT(n, 900);
  // And from the field: a point's pixel leads back to the point.
  for (double x = -4500; x <= 0; x += 450)
    for (double y = -3000; y <= 3000; y += 600) {
      const auto px = m.fieldToImage({x, y, 0});
      if (!px || px->u < 0 || px->v < 0 || px->u > 2447 || px->v > 2047) continue;
      const auto p = m.imageToField(*px, 0);
      ASSERT_TRUE(p.has_value());
      EXPECT_NEAR(p->x, x, 1e-6);
      EXPECT_NEAR(p->y, y, 1e-6);
    }
}

TEST(CameraLens, NoAnswerPastTheFold) {
  CameraCalibration c;
  c.focal_length = 1000, c.principal_point_x = 1000, c.principal_point_y = 1000;
  c.distortion = 0;
  c.lens.k2 = -0.2;  // r (1 - 0.2 r^4) stops growing at r^4 = 1
  const CameraModel m(c);
  // Inside the fold: a ray; beyond it: none, in either direction.
  EXPECT_TRUE(m.imageToField({1900, 1000}, 0).has_value());
  EXPECT_FALSE(m.imageToField({2100, 1000}, 0).has_value());
  // Undistorted radius 1.2 is more than the lens reaches (0.8 at the fold).
  EXPECT_FALSE(m.fieldToImage({1.2 * 4000, 0, 0}).has_value());
  const auto px = m.fieldToImage({0.5 * 4000, 0, 0});
  ASSERT_TRUE(px.has_value());
  const auto back = m.imageToField(*px, 0);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(back->x, 2000, 1e-6);
}

}  // namespace
}  // namespace dv

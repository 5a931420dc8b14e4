// Camera model: agreement with the worked examples of the league's model and
// exact round trips for either sign of distortion and tilted cameras.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "geometry/camera_model.h"

namespace dv {
namespace {

CameraCalibration cameraA(double k = 0) {
  CameraCalibration c;
  c.focal_length = 1000;
  c.principal_point_x = 1224;
  c.principal_point_y = 1024;
  c.distortion = k;
  c.q0 = 1, c.q1 = 0, c.q2 = 0, c.q3 = 0;
  c.tx = 0, c.ty = 0, c.tz = 4000;
  c.image_width = 2448, c.image_height = 2048;
  return c;
}

CameraCalibration cameraC() {
  CameraCalibration c;
  c.focal_length = 1100;
  c.principal_point_x = 1224;
  c.principal_point_y = 1024;
  c.distortion = 0.12;
  c.q0 = -0.703233, c.q1 = -0.703233, c.q2 = -0.073913, c.q3 = 0.073913;
  c.tx = 1000, c.ty = -3766.09, c.tz = 3288.855;
  return c;
}

void expectRel(double got, double want, double rel = 1e-6) {
  EXPECT_NEAR(got, want, rel * std::max(1.0, std::abs(want))) << "want " << want;
}

void expectPixel(const CameraModel& m, FieldPoint p, double u, double v) {
  auto px = m.fieldToImage(p);
  ASSERT_TRUE(px.has_value());
  expectRel(px->u, u);
  expectRel(px->v, v);
}

void expectField(const CameraModel& m, ImagePx px, double z, double x, double y) {
  auto f = m.imageToField(px, z);
  ASSERT_TRUE(f.has_value());
  expectRel(f->x, x);
  expectRel(f->y, y);
  expectRel(f->z, z);
}

TEST(CameraModel, WorkedExampleA) {
  CameraModel m(cameraA());
  expectPixel(m, {1000, 500, 0}, 1474, 899);
  expectPixel(m, {-2000, 1500, 0}, 724, 649);
  expectPixel(m, {1000, 500, 140}, 1483.067358, 894.466321);
  expectPixel(m, {4896, 0, 0}, 2448, 1024);
  expectField(m, {1724, 774}, 0, 2000, 1000);
  expectField(m, {1724, 774}, 140, 1930, 965);
  expectField(m, {2448, 2048}, 0, 4896, -4096);
  expectField(m, {0, 0}, 30, -4859.28, 4065.28);
}

TEST(CameraModel, WorkedExampleB) {
  CameraModel m(cameraA(0.2));
  expectPixel(m, {1000, 500, 0}, 1470.266172, 900.866914);
  expectPixel(m, {-2000, 1500, 0}, 756.026765, 673.020073);
  expectPixel(m, {1000, 500, 140}, 1478.925639, 896.537180);
  expectPixel(m, {4896, 0, 0}, 2238.916151, 1024);
  expectField(m, {1724, 774}, 0, 2125, 1062.5);
  expectField(m, {1724, 774}, 140, 2050.625, 1025.3125);
  expectField(m, {2448, 2048}, 0, 7389.779558, -6182.299238);
  expectField(m, {0, 0}, 30, -7334.356212, 6135.931994);
}

TEST(CameraModel, WorkedExampleCTiltedWithNearUnitQuaternion) {
  CameraModel m(cameraC());
  expectRel(m.position().x(), 2999.999598);
  expectRel(m.position().y(), -1000.002060);
  expectRel(m.position().z(), 4000.004887);
  expectPixel(m, {3000, -1000, 0}, 1224.000484, 791.434619);
  expectPixel(m, {2000, 0, 0}, 1510.908266, 504.755040);
  expectPixel(m, {4500, -2500, 0}, 840.039955, 1186.689474);
  expectPixel(m, {3500, -500, 140}, 1365.377026, 935.366000);
  expectField(m, {100, 100}, 0, 355.955414, -5157.726356);
  expectField(m, {2400, 2000}, 0, 9801.148585, 6013.678381);
  expectField(m, {1224, 1024.5}, 140, 3822.305245, -1000.002061);
}

TEST(CameraModel, PrincipalPointAndOpticalAxisMapToEachOther) {
  CameraModel m(cameraA(-0.1));
  auto px = m.fieldToImage({0, 0, 0});
  ASSERT_TRUE(px.has_value());
  EXPECT_DOUBLE_EQ(px->u, 1224);
  EXPECT_DOUBLE_EQ(px->v, 1024);
  auto f = m.imageToField({1224, 1024}, 0);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->x, 0, 1e-9);
  EXPECT_NEAR(f->y, 0, 1e-9);
}

TEST(CameraModel, DistortRadiusInvertsForBothSigns) {
  for (double k : {-0.3, -0.1, -0.02, 0.0, 1e-9, 0.05, 0.2, 1.0}) {
    for (double r = 0.001; r < 1.5; r += 0.01) {
      const double ru = CameraModel::undistortRadius(r, k);
      if (k < 0 && r > 1 / std::sqrt(-3 * k)) continue;  // beyond the model's fold
      auto rd = CameraModel::distortRadius(ru, k);
      ASSERT_TRUE(rd.has_value()) << k << " " << r;
      EXPECT_NEAR(*rd, r, 1e-12) << "k=" << k;
    }
  }
}

TEST(CameraModel, NegativeDistortionBeyondFoldIsRejected) {
  EXPECT_FALSE(CameraModel::distortRadius(10.0, -0.3).has_value());
}

// The largest image->field->image error over a dense pixel grid.
double maxRoundTripError(const CameraModel& m, int w, int h, double z) {
  double worst = 0;
  for (int v = 0; v <= h; v += 16) {
    for (int u = 0; u <= w; u += 16) {
      auto f = m.imageToField({double(u), double(v)}, z);
      if (!f) continue;  // above the horizon
      auto px = m.fieldToImage(*f);
      EXPECT_TRUE(px.has_value()) << u << "," << v;
      if (!px) continue;
      worst = std::max(worst, std::hypot(px->u - u, px->v - v));
    }
  }
  return worst;
}

TEST(CameraModel, RoundTripWholeImagePositiveAndNegativeDistortion) {
  for (double k : {-0.12, -0.05, 0.0, 0.08, 0.3}) {
    auto c = cameraA(k);
    c.focal_length = 1400;  // corners at |d| ~ 1.1: strong distortion there
    CameraModel m(c);
    for (double z : {0.0, 150.0}) {
      EXPECT_LT(maxRoundTripError(m, 2448, 2048, z), 1e-3) << "k=" << k << " z=" << z;
    }
  }
}

TEST(CameraModel, RoundTripTiltedCamerasIncludingHorizon) {
  for (double tilt_deg : {0.0, 20.0, 45.0, 75.0}) {
    for (double k : {-0.08, 0.15}) {
      // Camera 5 m high at the field edge, looking down by (90 - tilt) deg toward +x.
      const double tilt = tilt_deg * kPi / 180;
      Eigen::Matrix3d cam_to_field;
      // camera axes in field coordinates: x_c (image right), y_c (image down), z_c (view)
      Eigen::Vector3d zc(std::sin(tilt), 0, -std::cos(tilt));
      Eigen::Vector3d xc(0, -1, 0);
      Eigen::Vector3d yc = zc.cross(xc);
      cam_to_field.col(0) = xc;
      cam_to_field.col(1) = yc;
      cam_to_field.col(2) = zc;
      auto c = CameraCalibration::fromPose(0, 1300, 1250, 1000, k, cam_to_field.transpose(),
                                           {-5000, 200, 5000});
      CameraModel m(c);
      EXPECT_NEAR((m.position() - Eigen::Vector3d(-5000, 200, 5000)).norm(), 0, 1e-6);
      EXPECT_LT(maxRoundTripError(m, 2448, 2048, 0), 1e-3) << tilt_deg << " " << k;
      EXPECT_LT(maxRoundTripError(m, 2448, 2048, 150), 1e-3) << tilt_deg << " " << k;
    }
  }
}

TEST(CameraModel, PixelsAboveTheHorizonHaveNoFieldPoint) {
  const double tilt = 80 * kPi / 180;
  Eigen::Matrix3d cam_to_field;
  Eigen::Vector3d zc(std::sin(tilt), 0, -std::cos(tilt)), xc(0, -1, 0);
  cam_to_field << xc, zc.cross(xc), zc;
  CameraModel m(CameraCalibration::fromPose(0, 1000, 1224, 1024, 0, cam_to_field.transpose(),
                                            {-5000, 0, 3000}));
  EXPECT_FALSE(m.imageToField({1224, 0}, 0).has_value());  // image top looks at the sky
  EXPECT_TRUE(m.imageToField({1224, 2047}, 0).has_value());
  EXPECT_FALSE(m.fieldToImage({-6000, 0, 0}).has_value());  // behind the camera
}

}  // namespace
}  // namespace dv

// Four cameras over a Division A field: each calibrated automatically, then
// refined jointly. Bar: the mean offset between neighbouring cameras' field
// positions of the same points at 150 mm height, inside each overlap, is at
// most 3 mm; and jointly refining must not make the seams worse, also when a
// painted line is off its nominal place.
#include <gtest/gtest.h>

#include "calibration_scene.h"
#include "geometry/calibration/calibrate_camera.h"
#include "geometry/calibration/joint_refine.h"

namespace dv {
namespace {

std::vector<CameraCalibration> fourTopDownCameras(const FieldModel& f) {
  std::vector<CameraCalibration> out;
  const double ks[4] = {-0.05, 0.08, -0.02, 0.12};
  for (uint32_t id = 0; id < 4; ++id) {
    const FieldRect r = *f.cameraRegion(id, 4);
    const Eigen::Vector3d pos((r.x_min + r.x_max) / 2 + 40.0 * id, (r.y_min + r.y_max) / 2 - 30.0, 5000 - 100.0 * id);
    out.push_back(testing::makeCamera(id, 1224, 1024, 800 - 15.0 * id, ks[id], 611.5 + 6 * id, 511.5 - 5 * id,
                                      pos, 0.02 * id, 0.03 * id));
  }
  return out;
}

struct SeamStats {
  double worst = 0, mean = 0;
};

SeamStats seams(const std::vector<CameraCalibration>& truth, const std::vector<CameraCalibration>& est) {
  const int pairs[4][2] = {{0, 1}, {0, 2}, {1, 3}, {2, 3}};
  SeamStats s;
  for (const auto& p : pairs) {
    int n = 0;
    const double off = meanSeamOffset(truth[p[0]], est[p[0]], truth[p[1]], est[p[1]], 150, 50, &n);
    EXPECT_GT(n, 20) << "cameras " << p[0] << " and " << p[1] << " should overlap";
    s.worst = std::max(s.worst, off);
    s.mean += off / 4;
  }
  return s;
}

void calibrateAll(const FieldModel& painted, const FieldModel& nominal, const std::vector<CameraCalibration>& truth,
                  std::vector<CameraLines>& lines) {
  for (const auto& t : truth) {
    testing::SceneOptions so;
    so.robots = 4;
    so.seed = t.camera_id + 10;
    const cv::Mat img = testing::renderFieldImage(t, painted, so);
    CalibrationRequest req;
    req.camera_id = t.camera_id;
    req.num_cameras = 4;
    req.camera_height_mm = CameraModel(t).position().z();
    // The joint refinement judges the seams: misplaced painted lines leave a
    // single camera's pose less pinned than the automatic bar asks.
    req.refuse_unpinned = false;
    const auto out = calibrateCamera(img, nominal, req);
    ASSERT_FALSE(out.problem) << "camera " << t.camera_id << ": " << *out.problem;
    const FieldRect region = *nominal.cameraRegion(t.camera_id, 4);
    const LineObservation obs = observeLines(img, nominal, region);
    lines.push_back({out.calibration, obs.pixels, true});
  }
}

TEST(CalibrationJoint, FourCameraSeamsWithinThreeMillimetres) {
  const FieldModel f = FieldModel::divisionA();
  const auto truth = fourTopDownCameras(f);
  std::vector<CameraLines> lines;
  calibrateAll(f, f, truth, lines);
  ASSERT_EQ(lines.size(), 4u);
  std::vector<CameraCalibration> single;
  for (const auto& l : lines) single.push_back(l.calibration);
  const auto joint = refineJointly(lines, f);
  const SeamStats before = seams(truth, single), after = seams(truth, joint.calibrations);
  std::printf("seams at 150 mm: single mean %.3f worst %.3f mm; joint mean %.3f worst %.3f mm (%s)\n", before.mean,
              before.worst, after.mean, after.worst, joint.accepted ? "accepted" : "kept");
  EXPECT_LE(after.worst, 3.0);
}

TEST(CalibrationJoint, MisplacedPaintedLineSeamsDoNotOpen) {
  const FieldModel nominal = FieldModel::divisionA();
  FieldModel painted = nominal;
  // The halfway line and the center line painted 12 mm off.
  for (auto& l : painted.lines) {
    if (l.type == FieldShape::HalfwayLine) l.p1.x += 12, l.p2.x += 12;
    if (l.type == FieldShape::CenterLine) l.p1.y -= 12, l.p2.y -= 12;
  }
  const auto truth = fourTopDownCameras(nominal);
  std::vector<CameraLines> lines;
  calibrateAll(painted, nominal, truth, lines);
  ASSERT_EQ(lines.size(), 4u);
  std::vector<CameraCalibration> single;
  for (const auto& l : lines) single.push_back(l.calibration);
  const auto joint = refineJointly(lines, nominal);
  const SeamStats before = seams(truth, single), after = seams(truth, joint.calibrations);
  std::printf("misplaced lines, seams at 150 mm: single mean %.3f worst %.3f mm; joint mean %.3f worst %.3f mm\n",
              before.mean, before.worst, after.mean, after.worst);
  EXPECT_LE(after.mean, before.mean + 0.2);
  EXPECT_LE(after.worst, 3.0);
}

}  // namespace
}  // namespace dv

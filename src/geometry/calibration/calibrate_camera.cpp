#include "geometry/calibration/calibrate_camera.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "geometry/calibration/auto_extrinsics.h"
#include "geometry/calibration/line_fit.h"
#include "geometry/calibration/line_pixels.h"

namespace dv {

FieldRect cameraRegionFor(const FieldModel& field, uint32_t camera_id, unsigned num_cameras,
                          const std::string& source) {
  const unsigned n = num_cameras ? num_cameras : (field.field_length >= 12000 ? 4u : 2u);
  const auto region = field.cameraRegion(camera_id, n);
  if (!region)
    throw InputError(source, "camera id " + std::to_string(camera_id) + " has no field region with " +
                                 std::to_string(n) + " cameras");
  return *region;
}

LineObservation observeLines(const cv::Mat& image, const FieldModel& field, const FieldRect& region) {
  LineObservation obs;
  // Expected scale: the camera sees its region plus some overlap.
  const double area = (region.x_max - region.x_min) * (region.y_max - region.y_min) * 1.4;
  const double mm_per_px = std::sqrt(area / (double(image.cols) * image.rows));
  obs.half_width_px = halfLineWidthPx(mm_per_px, field.line_thickness);
  LinePixelOptions lp;
  lp.half_width_px = obs.half_width_px;
  obs.mask = detectLinePixels(image, lp);
  obs.distance = lineDistanceTransform(obs.mask);
  obs.pixels = maskPixels(obs.mask, 60000);
  obs.groups = groupSegments(detectLineSegments(obs.mask));
  // Pixels only for groups long enough to matter.
  const double min_extent = 0.15 * std::min(image.cols, image.rows);
  size_t keep = 0;
  while (keep < obs.groups.size() && obs.groups[keep].extent_px >= min_extent) ++keep;
  obs.groups.resize(keep);
  collectGroupPixels(obs.groups, obs.mask, obs.half_width_px + 1.5, 600);
  return obs;
}

namespace {

PixelDistortion estimateDistortion(const LineObservation& obs, int w, int h,
                                   std::optional<IntrinsicsResult>& out) {
  IntrinsicsOptions io;
  io.min_group_extent_px = 0.5 * std::min(w, h);
  out = calibrateDistortion(obs.groups, w, h, io);
  if (out) return out->distortion;
  return PixelDistortion{0, (w - 1) / 2.0, (h - 1) / 2.0};
}

void finish(CalibrationOutcome& r, const LineObservation& obs, const FieldModel& field,
            const FieldRect& region) {
  r.measures = measureCalibration(r.calibration, field, obs.pixels, obs.distance);
  QualityGateOptions g;
  g.region = region;
  r.problem = qualityProblem(r.calibration, r.measures, g);
}

// A camera looking (nearly) straight down sees the field the same from any
// height with the focal length scaled along (thesis §5.1.3); without the
// height its positions above the carpet would be guesses.
std::optional<std::string> unobservableHeight(const CameraCalibration& c, bool height_given) {
  if (height_given) return std::nullopt;
  const CameraModel cam(c);
  const Eigen::Vector3d axis = cam.rotation().transpose() * Eigen::Vector3d(0, 0, 1);
  const double tilt_deg = std::acos(std::clamp(-axis.z(), -1.0, 1.0)) * 180 / kPi;
  if (tilt_deg >= 12) return std::nullopt;
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "the camera looks nearly straight down (%.1f deg), so its height cannot be observed; "
                "give --camera-height",
                tilt_deg);
  return std::string(buf);
}

}  // namespace

CalibrationOutcome calibrateCamera(const cv::Mat& image, const FieldModel& field,
                                   const CalibrationRequest& req) {
  if (field.lines.empty()) throw InputError(req.source, "the field has no lines to calibrate on");
  const FieldRect region = cameraRegionFor(field, req.camera_id, req.num_cameras, req.source);
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
    throw InputError(req.source, "expected an 8-bit Bayer mosaic or BGR image");
  const int w = image.cols, h = image.rows;
  for (const auto& p : req.points)
    if (!(p.image.u >= 0 && p.image.v >= 0 && p.image.u <= w - 1 && p.image.v <= h - 1))
      throw InputError(req.source, "point (" + std::to_string(p.image.u) + ", " + std::to_string(p.image.v) +
                                       ") lies outside the " + std::to_string(w) + "x" + std::to_string(h) +
                                       " image");
  if (!req.points.empty() && req.points.size() < 4)
    throw InputError(req.source, "four or more points are needed, got " + std::to_string(req.points.size()));
  if (req.camera_height_mm && !(*req.camera_height_mm > 0))
    throw InputError(req.source, "the camera height must be positive");

  const LineObservation obs = observeLines(image, field, region);
  if (obs.pixels.size() < 300 || obs.groups.empty())
    throw InputError(req.source, "no field lines found in the image (" + std::to_string(obs.pixels.size()) +
                                     " line pixels, " + std::to_string(obs.groups.size()) + " line groups)");

  CalibrationOutcome r;
  const PixelDistortion distortion = estimateDistortion(obs, w, h, r.intrinsics);
  const FieldLineModel model(field);
  LineFitOptions lf;
  lf.fix_height = req.camera_height_mm.has_value();
  lf.image_width = w, lf.image_height = h;

  if (!req.points.empty()) {
    PointPoseOptions po;
    po.camera_height_mm = req.camera_height_mm;
    po.image_width = w, po.image_height = h;
    const auto pose = solvePointPose(req.points, distortion, po);
    if (!pose) {
      r.problem = "no camera pose fits the given points";
      return r;
    }
    const auto fit = refineOnLines(pose->params, obs.pixels, model, req.points, lf);
    r.refinement_accepted = fit.improved;
    r.calibration = fit.params.toCalibration(req.camera_id, w, h);
    finish(r, obs, field, region);
    if (!r.problem) r.problem = unobservableHeight(r.calibration, req.camera_height_mm.has_value());
    return r;
  }

  r.automatic = true;
  AutoExtrinsicsOptions ao;
  ao.camera_height_mm = req.camera_height_mm;
  const auto found = findPoseAutomatically(obs, distortion, field, region, w, h, ao);
  if (!found.params) {
    r.problem = "cannot decide the camera pose from the lines alone (" + found.reason +
                "); give four points with --corners or --point";
    return r;
  }
  r.refinement_accepted = true;
  r.calibration = found.params->toCalibration(req.camera_id, w, h);
  finish(r, obs, field, region);
  if (!r.problem) r.problem = unobservableHeight(r.calibration, req.camera_height_mm.has_value());
  if (r.problem)
    r.problem = "cannot decide the camera pose from the lines alone (" + *r.problem +
                "); give four points with --corners or --point";
  return r;
}

}  // namespace dv

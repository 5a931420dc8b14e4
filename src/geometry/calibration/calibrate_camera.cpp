#include "geometry/calibration/calibrate_camera.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "geometry/calibration/auto_extrinsics.h"
#include "geometry/calibration/line_fit.h"
#include "geometry/calibration/line_pixels.h"
#include "geometry/calibration/pose_uncertainty.h"
#include <spdlog/spdlog.h>

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
  // Expected scale: the camera sees its region plus some overlap.
  const double area = (region.x_max - region.x_min) * (region.y_max - region.y_min) * 1.4;
  return observeLinesAtScale(image, field, std::sqrt(area / (double(image.cols) * image.rows)));
}

LineObservation observeLinesAtScale(const cv::Mat& image, const FieldModel& field, double mm_per_px) {
  LineObservation obs;
  obs.half_width_px = halfLineWidthPx(mm_per_px, field.line_thickness);
  LinePixelOptions lp;
  lp.half_width_px = obs.half_width_px;
  obs.mask = detectLinePixels(image, lp);
  obs.distance = lineDistanceTransform(obs.mask);
  obs.mask_pixels = maskPixels(obs.mask, 60000);
  obs.pixels = obs.mask_pixels;
  refineToLineCentres(lineBrightness(image), obs.half_width_px, obs.pixels);
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
            const std::optional<FieldRect>& region) {
  r.measures = measureCalibration(r.calibration, field, obs.pixels, obs.distance);
  QualityGateOptions g;
  g.region = region;
  r.problem = qualityProblem(r.calibration, r.measures, g);
}

// Lens terms beyond the league's model. The lens fit's bins take the mean of
// the mask pixels across the painted width (they need both sides of the
// line), and with a lens the league's model does not fit, where its nested
// fits end depends on their start (k2 trades against k and the lines'
// offsets): it gets the mask pixels and its own league start fitted on
// them. Its terms are kept only when they also fit the sub-pixel line
// centres better than the league fit does: a lens fit that wandered off
// along a direction the mask pixels do not fix (the principal point of a
// grazing view) fits them worse. Otherwise the sub-pixel league fit stays.
LensFitResult fitLens(const CameraParams& league, const LineObservation& obs, const FieldLineModel& model,
                      const std::vector<PointCorrespondence>& points, const LineFitOptions& lf) {
  const CameraParams start = refineOnLines(league, obs.mask_pixels, model, points, lf).params;
  LensFitResult lens = fitLensOnLines(start, obs.mask_pixels, model, points, lf);
  if (lens.lens_used) {
    const double gate = lf.gates_px.back(), scale = lf.loss_scale_px;
    const double with_terms = robustLineCost(lens.params, obs.pixels, model, gate, scale);
    const double without = robustLineCost(league, obs.pixels, model, gate, scale);
    spdlog::debug("lens terms on the line centres: cost {:.5f} with, {:.5f} without", with_terms, without);
    if (!(with_terms < without)) lens.lens_used = false;
  }
  if (!lens.lens_used) lens.params = lens.league = league;
  return lens;
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

// A pose the lines fit but do not pin down (too little of the field in
// view) is refused rather than written. Its predicted field error (one
// sigma, from the line centres' scatter) must stay within half the
// millimetre the calibration promises on the carpet, where on the pose
// sweep the error found ran up to 2.7 times the prediction (corner views),
// and within the millimetre at robot height, where the prediction adds the
// height's coupling to the tilt and runs above the error found.
constexpr double kMaxPredictedCarpetErrorMm = 0.5;
constexpr double kMaxPredicted150ErrorMm = 1.0;

std::optional<std::string> poorlyPinned(CalibrationOutcome& r, const LineObservation& obs, const FieldLineModel& model,
                                        const FieldModel& field, const CalibrationRequest& req, int w, int h) {
  PoseUncertaintyOptions uo;
  uo.height_fixed = req.camera_height_mm.has_value();
  uo.width = w, uo.height = h;
  r.predicted_error =
      predictFieldError(CameraParams::fromCalibration(r.calibration), obs.pixels, model, field.withBoundary(), uo);
  if (!r.predicted_error) return std::string("too few line pixels fit to judge the pose");
  const auto& e = *r.predicted_error;
  spdlog::debug("predicted field error {:.3f} mm at z=0, {:.3f} mm at z=150 (noise {:.2f} px, {} px)", e.at_carpet_mm,
                e.at_150_mm, e.noise_px, e.pixels_used);
  if (e.at_carpet_mm <= kMaxPredictedCarpetErrorMm && e.at_150_mm <= kMaxPredicted150ErrorMm) return std::nullopt;
  char buf[240];
  std::snprintf(buf, sizeof buf,
                "the lines in view do not pin the pose down (predicted field error %.2f mm at z=0, %.2f mm at "
                "z=150)%s",
                e.at_carpet_mm, e.at_150_mm, uo.height_fixed ? "" : "; give --camera-height");
  return std::string(buf);
}

// Field size of an image pixel the points imply (mean over point pairs).
double pointsScale(const std::vector<PointCorrespondence>& pts) {
  double sum = 0;
  int n = 0;
  for (size_t i = 0; i < pts.size(); ++i)
    for (size_t j = i + 1; j < pts.size(); ++j) {
      const double px = std::hypot(pts[i].image.u - pts[j].image.u, pts[i].image.v - pts[j].image.v);
      if (px < 1) continue;
      sum += std::hypot(pts[i].field.x - pts[j].field.x, pts[i].field.y - pts[j].field.y) / px;
      ++n;
    }
  return n ? sum / n : 0;
}

// Where the automatic search looks, and what settles the symmetry.
struct SearchPlan {
  FieldRect region;
  bool by_region = true;  // the view center must lie in the region (else near target)
  FieldMm target{0, 0};
  std::string basis;
};

// A region's sides on the field's outer lines reach on outwards: a view
// centre beyond the goal or touch line still lies in the region.
FieldRect openOuterEdges(FieldRect r, const FieldModel& field) {
  const double l = field.field_length / 2.0, w = field.field_width / 2.0, far = 1e9;
  if (r.x_min <= -l) r.x_min = -far;
  if (r.x_max >= l) r.x_max = far;
  if (r.y_min <= -w) r.y_min = -far;
  if (r.y_max >= w) r.y_max = far;
  return r;
}

SearchPlan planSearch(const FieldModel& field, const CalibrationRequest& req) {
  SearchPlan plan;
  const auto center = [](const FieldRect& r) { return FieldMm{(r.x_min + r.x_max) / 2, (r.y_min + r.y_max) / 2}; };
  char buf[200];
  switch (req.hint.kind) {
    case ViewHint::Kind::Region:
      plan.region = req.hint.region;
      plan.target = center(plan.region);
      plan.basis = req.hint.describe();
      break;
    case ViewHint::Kind::Near: {
      // A camera's share of the field in the layout, centered on the point.
      const FieldRect size = cameraRegionFor(field, 0, req.num_cameras, req.source);
      const double hx = (size.x_max - size.x_min) / 2, hy = (size.y_max - size.y_min) / 2;
      plan.target = req.hint.near;
      plan.region = {plan.target.x - hx, plan.target.x + hx, plan.target.y - hy, plan.target.y + hy};
      plan.by_region = false;  // "roughly where it looks"
      plan.basis = req.hint.describe();
      break;
    }
    case ViewHint::Kind::None: {
      plan.region = cameraRegionFor(field, req.camera_id, req.num_cameras, req.source);
      plan.target = center(plan.region);
      const unsigned n = req.num_cameras ? req.num_cameras : (field.field_length >= 12000 ? 4u : 2u);
      std::snprintf(buf, sizeof buf, "the camera-id layout (camera %u of %u covers x %.0f..%.0f, y %.0f..%.0f)",
                    req.camera_id, n, plan.region.x_min, plan.region.x_max, plan.region.y_min, plan.region.y_max);
      plan.basis = buf;
      break;
    }
  }
  return plan;
}

}  // namespace

CalibrationOutcome calibrateCamera(const cv::Mat& image, const FieldModel& field,
                                   const CalibrationRequest& req) {
  if (field.lines.empty()) throw InputError(req.source, "the field has no lines to calibrate on");
  const bool with_points = !req.points.empty();
  const SearchPlan plan = with_points ? SearchPlan{} : planSearch(field, req);
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
    throw InputError(req.source, "expected an 8-bit Bayer mosaic or BGR image");
  const int w = image.cols, h = image.rows;
  for (const auto& p : req.points)
    if (!(p.image.u >= 0 && p.image.v >= 0 && p.image.u <= w - 1 && p.image.v <= h - 1))
      throw InputError(req.source, "point (" + std::to_string(p.image.u) + ", " + std::to_string(p.image.v) +
                                       ") lies outside the " + std::to_string(w) + "x" + std::to_string(h) +
                                       " image");
  if (with_points && req.points.size() < 4)
    throw InputError(req.source, "four or more points are needed, got " + std::to_string(req.points.size()));
  if (req.camera_height_mm && !(*req.camera_height_mm > 0))
    throw InputError(req.source, "the camera height must be positive");

  CalibrationOutcome r;
  if (with_points) {
    if (const auto why = pointSetProblem(req.points, w, h)) {
      r.problem = "the points cannot fix a camera pose: " + *why;
      return r;
    }
  }
  r.lines = with_points ? observeLinesAtScale(image, field, pointsScale(req.points))
                        : observeLines(image, field, plan.region);
  const LineObservation& obs = r.lines;
  if (obs.pixels.size() < 300 || obs.groups.empty())
    throw InputError(req.source, "no field lines found in the image (" + std::to_string(obs.pixels.size()) +
                                     " line pixels, " + std::to_string(obs.groups.size()) + " line groups)");

  const PixelDistortion distortion = estimateDistortion(obs, w, h, r.intrinsics);
  const FieldLineModel model(field);
  LineFitOptions lf;
  lf.fix_height = req.camera_height_mm.has_value();
  lf.image_width = w, lf.image_height = h;

  if (with_points) {
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
    r.lens = fitLens(fit.params, obs, model, req.points, lf);
    r.calibration = r.lens->params.toCalibration(req.camera_id, w, h);
    r.has_pose = true;
    r.symmetry = decidedByPoints(fit.params, w, h);
    // The points say where the camera is: no region to check against.
    finish(r, obs, field, std::nullopt);
    if (!r.problem) r.problem = unobservableHeight(r.calibration, req.camera_height_mm.has_value());
    return r;
  }

  r.automatic = true;
  const auto refuse = [&r](const std::string& why) {
    r.problem = "cannot decide the camera pose from the lines alone (" + why +
                "); give four points with --corners or --point";
  };
  AutoExtrinsicsOptions ao;
  ao.camera_height_mm = req.camera_height_mm;
  const auto found = findPoseAutomatically(obs, distortion, field, w, h, ao);
  if (found.readings.empty()) {
    refuse(found.reason);
    return r;
  }
  if (!plan.by_region && found.readings.size() > 1) {
    refuse("different poses fit the lines about equally well, and --near cannot tell them apart");
    return r;
  }
  const SymmetryChoice choice =
      plan.by_region ? chooseInRegion(found.readings, openOuterEdges(plan.region, field), plan.basis, w, h)
                     : chooseNearTarget(found.readings[0], plan.target, plan.basis, w, h);
  r.symmetry = choice.decision;
  r.refinement_accepted = true;
  r.calibration = choice.params.toCalibration(req.camera_id, w, h);
  r.has_pose = true;
  if (!choice.decision.decided) {
    r.problem = "the field's half-turn symmetry cannot be settled by " + plan.basis + ": " +
                choice.decision.reason + "; give --near X,Y (roughly where the camera looks) or four points";
    return r;
  }
  r.lens = fitLens(choice.params, obs, model, {}, lf);
  r.calibration = r.lens->params.toCalibration(req.camera_id, w, h);
  // Without the height, a view straight down drifts along its unobserved
  // height; ask for it before judging the drifted fit.
  spdlog::debug("distortion start: kappa {:.3g}, pp ({:.1f}, {:.1f}); final f {:.1f}, k {:.4f}, pp ({:.1f}, {:.1f})",
                distortion.kappa, distortion.cx, distortion.cy, r.calibration.focal_length, r.calibration.distortion,
                r.calibration.principal_point_x, r.calibration.principal_point_y);
  auto height_problem = unobservableHeight(r.calibration, req.camera_height_mm.has_value());
  const double z = CameraModel(r.calibration).position().z();
  if (!height_problem && !req.camera_height_mm && !(z >= 500 && z <= 20000)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "the lines do not fix the camera height (the fit drifts to %.0f mm); give --camera-height", z);
    height_problem = std::string(buf);
  }
  // The symmetry choice has placed the view in the region: no region gate.
  finish(r, obs, field, std::nullopt);
  if (height_problem) r.problem = height_problem;
  if (!r.problem) {
    auto unpinned = poorlyPinned(r, obs, model, field, req, w, h);
    if (req.refuse_unpinned) r.problem = std::move(unpinned);
  }
  if (r.problem) refuse(*r.problem);
  return r;
}

}  // namespace dv

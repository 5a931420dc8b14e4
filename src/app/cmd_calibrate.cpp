// `dotvision calibrate --image F --geometry FIELD.json --camera-id N
//   [--corners u1,v1,...,u4,v4] [--point X,Y=U,V ...] [--camera-height MM]
//   [--region R | --near X,Y] [--report REPORT.json] --out CALIB.json`: one
// camera's calibration from one image of the field. Writes SSL_GeometryData
// (the field plus this camera), an overlay PNG of the model lines over the
// image, and prints the measures and the report (also as JSON with
// --report). Nothing but the report is written when the calibration is
// refused (exit 1).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "core/error.h"
#include "geometry/calibration/calibrate_camera.h"
#include "geometry/calibration/calibration_report.h"
#include "geometry/calibration/line_pixels.h"
#include "geometry/geometry_io.h"
#include "io/image_decode.h"

namespace dv::app {

namespace {

struct CalibrateOptions {
  std::string image, geometry, out, overlay;
  int camera_id = -1;
  unsigned num_cameras = 0;
  std::string corners;
  std::vector<std::string> points;
  double camera_height = 0;
  std::string region, near, report;
};

std::vector<double> parseNumbers(const std::string& text, char sep, const std::string& what) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, sep)) {
    try {
      size_t used = 0;
      const double v = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(v)) throw std::invalid_argument(item);
      out.push_back(v);
    } catch (const std::exception&) {
      throw InputError("command line", what + ": '" + item + "' is not a number");
    }
  }
  return out;
}

PointCorrespondence parsePoint(const std::string& text) {
  const auto eq = text.find('=');
  const std::string what = "--point " + text;
  if (eq == std::string::npos) throw InputError("command line", what + ": expected X,Y=U,V");
  const auto field = parseNumbers(text.substr(0, eq), ',', what);
  const auto image = parseNumbers(text.substr(eq + 1), ',', what);
  if ((field.size() != 2 && field.size() != 3) || image.size() != 2)
    throw InputError("command line", what + ": expected X,Y=U,V (field mm = image px)");
  return {{field[0], field[1], field.size() == 3 ? field[2] : 0.0}, {image[0], image[1]}};
}

std::string defaultOverlayPath(const std::string& out) {
  const auto dot = out.find_last_of('.');
  const auto slash = out.find_last_of('/');
  const std::string stem = (dot != std::string::npos && (slash == std::string::npos || dot > slash))
                               ? out.substr(0, dot)
                               : out;
  return stem + ".overlay.png";
}

}  // namespace

CommandFn addCalibrateCommand(CLI::App& root) {
  auto opt = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = root.add_subcommand("calibrate", "Calibrate one camera from an image of the field lines");
  cmd->add_option("--image", opt->image, "Image (8-bit single channel = Bayer RGGB, or colour)")->required();
  cmd->add_option("--geometry", opt->geometry, "Field (SSL_GeometryData JSON/YAML; calibrations ignored)")
      ->required();
  cmd->add_option("--camera-id", opt->camera_id, "Camera id (SSL-Vision layout decides its field region)")
      ->required()
      ->check(CLI::Range(0, 63));
  cmd->add_option("--num-cameras", opt->num_cameras,
                  "Cameras on the field (1, 2, 4, 6, 8; default 4 for Division A size, else 2)");
  cmd->add_option("--corners", opt->corners,
                  "u1,v1,...,u4,v4: image positions of the region's corners (--region, else the camera id's), "
                  "counter-clockwise from the smallest field x and y");
  cmd->add_option("--point", opt->points, "X,Y=U,V: a field point (mm) and its image position (px); 4+")
      ->take_all();
  cmd->add_option("--camera-height", opt->camera_height, "Camera height in mm (needed looking straight down)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", opt->out, "Output SSL_GeometryData (.json canonical JSON, or .yaml)")->required();
  cmd->add_option("--overlay", opt->overlay, "Overlay PNG (default: OUT with .overlay.png)");
  cmd->add_option("--region", opt->region,
                  std::string("Where the camera looks, settling the field's half-turn symmetry instead of the "
                              "camera-id layout (quote it in a shell): ") +
                      regionHintNames());
  cmd->add_option("--near", opt->near, "X,Y: roughly where the camera looks (field mm), instead of the layout");
  cmd->add_option("--report", opt->report, "Write the calibration report as JSON (also when refused)");
  return [opt] {
    if (!opt->corners.empty() && !opt->points.empty())
      throw InputError("command line", "give either --corners or --point, not both");
    if (!opt->region.empty() && !opt->near.empty())
      throw InputError("command line", "give either --region or --near, not both");
    Geometry geometry = loadGeometry(opt->geometry);
    geometry.cameras.clear();
    if (geometry.field.lines.empty())
      throw InputError(opt->geometry, "the field has no lines to calibrate on");
    const cv::Mat image = calibrationImage(readImageFile(opt->image), opt->image);

    CalibrationRequest req;
    req.camera_id = uint32_t(opt->camera_id);
    req.num_cameras = opt->num_cameras;
    req.source = opt->image;
    if (opt->camera_height > 0) req.camera_height_mm = opt->camera_height;
    if (!opt->region.empty()) req.hint = parseRegionHint(opt->region, geometry.field, "command line");
    if (!opt->near.empty()) req.hint = parseNearHint(opt->near, geometry.field, "command line");
    if (!opt->corners.empty()) {
      const auto v = parseNumbers(opt->corners, ',', "--corners");
      if (v.size() != 8) throw InputError("command line", "--corners: expected 8 numbers u1,v1,...,u4,v4");
      if (req.hint.kind == ViewHint::Kind::Near)
        throw InputError("command line", "--corners are the corners of a region: give --region, not --near");
      const FieldRect r = req.hint.kind == ViewHint::Kind::Region
                              ? req.hint.region
                              : cameraRegionFor(geometry.field, req.camera_id, req.num_cameras, "command line");
      const auto corners = regionCornersCounterClockwise(r.x_min, r.x_max, r.y_min, r.y_max);
      for (int i = 0; i < 4; ++i) req.points.push_back({corners[i], {v[2 * i], v[2 * i + 1]}});
    }
    for (const auto& p : opt->points) req.points.push_back(parsePoint(p));
    if (!opt->points.empty() && opt->points.size() < 4)
      throw InputError("command line", "--point: four or more are needed, got " + std::to_string(opt->points.size()));

    const auto start = std::chrono::steady_clock::now();
    const CalibrationOutcome out = calibrateCamera(image, geometry.field, req);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto& m = out.measures;
    std::printf(
        "{\"camera_id\":%d,\"mode\":\"%s\",\"seconds\":%.2f,\"overlap_ratio\":%.4f,"
        "\"mean_distance_px\":%.3f,\"mean_distance_mm\":%.3f,\"line_pixels\":%d,\"model_support\":%.3f,"
        "\"refinement_accepted\":%s,\"passed\":%s}\n",
        opt->camera_id, out.automatic ? "automatic" : "points", seconds, m.overlap_ratio, m.mean_distance_px,
        m.mean_distance_mm, m.line_pixels, m.model_support, out.refinement_accepted ? "true" : "false",
        out.problem ? "false" : "true");
    const CalibrationReport report =
        makeCalibrationReport(out, geometry.field, opt->image, uint32_t(opt->camera_id), seconds);
    std::fputs(formatReport(report).c_str(), stdout);
    std::fflush(stdout);
    if (!opt->report.empty()) {
      std::ofstream f(opt->report);
      f << reportToJson(report).dump(2) << "\n";
      if (!f) throw InputError(opt->report, "cannot write the report");
    }
    if (out.problem) {
      std::fprintf(stderr, "dotvision calibrate: %s: no calibration written: %s\n", opt->image.c_str(),
                   out.problem->c_str());
      return kExitFailure;
    }
    geometry.cameras.push_back(out.calibration);
    saveGeometry(geometry, opt->out);
    const std::string overlay = opt->overlay.empty() ? defaultOverlayPath(opt->out) : opt->overlay;
    if (!cv::imwrite(overlay, drawModelOverlay(toBgrImage(image, opt->image), out.calibration, geometry.field)))
      throw InputError(overlay, "cannot write the overlay image");
    return kExitOk;
  };
}

}  // namespace dv::app

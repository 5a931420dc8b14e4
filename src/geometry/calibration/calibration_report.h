#pragma once
// What a calibration run found and decided, for the operator (printed by
// `dotvision calibrate`) and for tools (JSON): the lines found and used, the
// residual of each line group against the model line it matches, the
// estimated parameters, the symmetry decision and the verdict with its
// reason.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geometry/calibration/calibrate_camera.h"
#include "geometry/calibration/league_fit.h"

namespace dv {

struct LineGroupResidual {
  double extent_px = 0;
  int pixels = 0;           // pixels of the group
  int matched = 0;          // of those, within the gate of a model line
  std::string line;         // the model line most of them match ("" none)
  double mean_px = 0, mean_mm = 0;  // over the matched pixels
  bool used = false;        // the calibration explains this group
};

struct CalibrationReport {
  std::string image;
  uint32_t camera_id = 0;
  std::string mode;  // "points" or "automatic"
  double seconds = 0;
  int line_pixels = 0;
  std::vector<LineGroupResidual> groups;  // longest first
  int groups_used = 0;
  int distortion_groups = 0;         // long groups the lens was fitted on
  double distortion_rms_px = 0;      // their straightness after the fit
  bool has_calibration = false;      // a pose was found (passed or not)
  CameraCalibration calibration;
  double tilt_deg = 0, heading_deg = 0;  // optical axis: from straight down; its direction on the field from +x
  CalibrationMeasures measures;
  std::optional<LensFitResult> lens;    // the test of the lens terms, both line residuals
  std::optional<LeagueFit> league_fit;  // what packets carry, with its field residual
  std::optional<SymmetryDecision> symmetry;
  bool passed = false;
  std::string verdict;  // "passed" or the reason for refusing
};

CalibrationReport makeCalibrationReport(const CalibrationOutcome& outcome, const FieldModel& field,
                                        const std::string& image, uint32_t camera_id, double seconds);

std::string formatReport(const CalibrationReport& report);
nlohmann::json reportToJson(const CalibrationReport& report);

}  // namespace dv

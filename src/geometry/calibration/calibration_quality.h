#pragma once
// Measures of how well a calibration fits an image's line pixels, and the
// gate every calibration must pass before it is written or sent.
#include <optional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/units.h"
#include "geometry/calibration/field_line_model.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"

namespace dv {

struct CalibrationMeasures {
  // Thesis §4.3.2: share of all line pixels that lie on a model line.
  double overlap_ratio = 0;
  // Mean distance of the line pixels near the model (within the gate) to it.
  double mean_distance_px = 0;
  double mean_distance_mm = 0;
  int line_pixels = 0;
  int matched_pixels = 0;
  // Share of the model lines in view that have line pixels under them: low
  // when the calibration explains only part of what it should see.
  double model_support = 0;
  int model_samples_in_view = 0;
};

// `line_distance` is the distance transform of the non-line pixels (CV_32F,
// distance to the nearest line pixel), used for model_support.
CalibrationMeasures measureCalibration(const CameraCalibration& calibration, const FieldModel& field,
                                       const std::vector<ImagePx>& line_pixels,
                                       const cv::Mat& line_distance, double gate_px = 10);

cv::Mat lineDistanceTransform(const cv::Mat& line_mask);

struct QualityGateOptions {
  double min_overlap_ratio = 0.35;
  double max_mean_distance_px = 1.5;
  double min_model_support = 0.5;
  int min_model_samples = 40;
  // The camera's field region (camera id, SSL-Vision layout); its center must
  // be in view.
  std::optional<FieldRect> region;
};

// nullopt when the calibration passes, otherwise the reason it does not.
std::optional<std::string> qualityProblem(const CameraCalibration& calibration,
                                          const CalibrationMeasures& measures,
                                          const QualityGateOptions& options);

// Mean distance (mm) between two calibrations' field positions of a grid of
// image pixels at the given height, over pixels whose reference position
// lies inside `area`. Used for accuracy against a known truth and for the
// offset between neighbouring cameras.
double meanFieldPositionError(const CameraCalibration& reference, const CameraCalibration& other,
                              double height_mm, const FieldRect& area, int grid_step_px = 32,
                              int* samples = nullptr);

// The image with the model lines drawn over it (BGR).
cv::Mat drawModelOverlay(const cv::Mat& bgr, const CameraCalibration& calibration,
                         const FieldModel& field);

}  // namespace dv

#pragma once
// Calibration from the console: one run per camera at a time, on a worker
// thread of its own (it takes seconds; the detection threads never wait for
// it), on the camera's newest frame. A run that passed waits for the
// operator: accept (the caller hands the calibration to the runtime) or
// reject. States: "none", "running", "failed" (the input was unusable),
// "done" (a report; passed or refused), "accepted", "rejected".
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "geometry/calibration/calibrate_camera.h"
#include "io/frame_source.h"

namespace dv::app {

class CalibrationRuns {
 public:
  ~CalibrationRuns();

  // Starts a run on `frame` (any camera pixel format); false when one is
  // still running for that camera.
  bool start(const Frame& frame, const FieldModel& field, const CalibrationRequest& request);
  // {"state", "camera_id", "report" (calibration_report.h's JSON), "lines"
  // (the segments found, [u1,v1,u2,v2] in image px), "error", "image_size"}.
  nlohmann::json describe(uint32_t camera_id) const;
  // The frame with the segments found and the model lines through the new
  // calibration drawn over it, at most max_width wide; empty when no run.
  cv::Mat overlay(uint32_t camera_id, const FieldModel& field, int max_width) const;
  // The calibration of a "done" run that passed (nullopt otherwise, with why).
  std::optional<CameraCalibration> acceptable(uint32_t camera_id, std::string& why) const;
  // "accepted" or "rejected"; false when no finished run is there to settle.
  bool settle(uint32_t camera_id, bool accepted);

 private:
  struct Run {
    uint32_t camera_id = 0;
    std::string state = "running";
    cv::Mat bgr;
    nlohmann::json report, lines = nlohmann::json::array();
    std::string error;
    bool passed = false;
    std::optional<CameraCalibration> calibration;  // a pose was found
    std::thread worker;
  };
  Run* find(uint32_t camera_id) const;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<Run>> runs_;
};

}  // namespace dv::app

#include "app/console_calibration.h"

#include <chrono>
#include <opencv2/imgproc.hpp>

#include "app/debug_views.h"
#include "core/error.h"
#include "geometry/calibration/calibration_report.h"
#include "geometry/geometry_io.h"

namespace dv::app {

namespace {

// What the cameras use is what is published: single-precision floats.
CameraCalibration asPublished(const FieldModel& field, const CameraCalibration& c) {
  Geometry g;
  g.field = field;
  g.cameras = {c};
  return withWirePrecision(g, "calibration").cameras.front();
}

}  // namespace

CalibrationRuns::~CalibrationRuns() {
  for (auto& r : runs_)
    if (r->worker.joinable()) r->worker.join();
}

CalibrationRuns::Run* CalibrationRuns::find(uint32_t camera_id) const {
  for (const auto& r : runs_)
    if (r->camera_id == camera_id) return r.get();
  return nullptr;
}

bool CalibrationRuns::start(const Frame& frame, const FieldModel& field, const CalibrationRequest& request) {
  std::lock_guard<std::mutex> lock(mutex_);
  Run* run = find(request.camera_id);
  if (run && run->state == "running") return false;
  if (!run) {
    runs_.push_back(std::make_unique<Run>());
    run = runs_.back().get();
    run->camera_id = request.camera_id;
  }
  if (run->worker.joinable()) run->worker.join();  // finished: its state is not "running"
  run->state = "running";
  run->report = nullptr;
  run->lines = nlohmann::json::array();
  run->error.clear();
  run->passed = false;
  run->calibration.reset();
  run->bgr = frameToBgr(frame).clone();
  run->worker = std::thread([this, run, field, request, image = run->bgr] {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      const CalibrationOutcome out = calibrateCamera(image, field, request);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const CalibrationReport report = makeCalibrationReport(out, field, request.source, request.camera_id, seconds);
      nlohmann::json lines = nlohmann::json::array();
      for (const LineGroup& g : out.lines.groups)
        for (const LineSegment& s : g.segments) lines.push_back({s.a.u, s.a.v, s.b.u, s.b.v});
      std::lock_guard<std::mutex> lock(mutex_);
      run->report = reportToJson(report);
      run->lines = std::move(lines);
      run->passed = !out.problem;
      if (out.has_pose) run->calibration = asPublished(field, out.calibration);
      run->state = "done";
    } catch (const std::exception& e) {  // InputError: no lines, points outside the image
      std::lock_guard<std::mutex> lock(mutex_);
      run->error = e.what();
      run->state = "failed";
    }
  });
  return true;
}

nlohmann::json CalibrationRuns::describe(uint32_t camera_id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const Run* run = find(camera_id);
  if (!run) return {{"camera_id", camera_id}, {"state", "none"}};
  nlohmann::json j = {{"camera_id", camera_id},
                      {"state", run->state},
                      {"passed", run->passed},
                      {"image_size", {run->bgr.cols, run->bgr.rows}},
                      {"lines", run->lines},
                      {"report", run->report}};
  if (!run->error.empty()) j["error"] = run->error;
  return j;
}

cv::Mat CalibrationRuns::overlay(uint32_t camera_id, const FieldModel& field, int max_width) const {
  cv::Mat img;
  std::optional<CameraCalibration> calibration;
  nlohmann::json lines;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const Run* run = find(camera_id);
    if (!run || run->bgr.empty()) return {};
    img = run->bgr.clone();
    calibration = run->calibration;
    lines = run->lines;
  }
  if (calibration) img = drawModelOverlay(img, *calibration, field);
  const int thickness = std::max(1, img.cols / 400);
  for (const auto& l : lines)
    cv::line(img, cv::Point2d(l[0].get<double>(), l[1].get<double>()),
             cv::Point2d(l[2].get<double>(), l[3].get<double>()), cv::Scalar(0, 200, 255), thickness, cv::LINE_AA);
  if (max_width > 0 && img.cols > max_width) {
    const double scale = double(max_width) / img.cols;
    cv::resize(img, img, cv::Size(max_width, std::max(1, int(img.rows * scale + 0.5))), 0, 0, cv::INTER_AREA);
  }
  return img;
}

std::optional<CameraCalibration> CalibrationRuns::acceptable(uint32_t camera_id, std::string& why) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const Run* run = find(camera_id);
  const std::string name = "camera " + std::to_string(camera_id);
  if (!run) why = name + " has no calibration run to accept: start one with POST .../calibrate";
  else if (run->state == "running") why = name + ": the calibration is still running";
  else if (run->state != "done") why = name + ": no new calibration to accept (the run is " + run->state + ")";
  else if (!run->passed || !run->calibration)
    why = name + ": the calibration was refused (" + run->report["verdict"]["reason"].get<std::string>() + ")";
  else return run->calibration;
  return std::nullopt;
}

bool CalibrationRuns::settle(uint32_t camera_id, bool accepted) {
  std::lock_guard<std::mutex> lock(mutex_);
  Run* run = find(camera_id);
  if (!run || run->state != "done") return false;
  run->state = accepted ? "accepted" : "rejected";
  return true;
}

}  // namespace dv::app

#include "app/console_layers.h"

#include <chrono>
#include <optional>

#include "app/camera_feed.h"
#include "core/error.h"
#include "pipeline/cpu_pipeline.h"

namespace dv::app {

namespace {

bool sameOptions(const PipelineOptions& a, const PipelineOptions& b) {
  return a.color == b.color && a.score == b.score && a.bayer == b.bayer && a.bayer_sampling == b.bayer_sampling &&
         a.plane_height == b.plane_height && a.threshold == b.threshold && a.max_blobs == b.max_blobs &&
         a.weak_threshold == b.weak_threshold && a.max_weak_blobs == b.max_weak_blobs;
}

// The colors divided by their brightness, gray at 128: what the pipeline's
// brightness-invariant chroma sees (a shadow looks like the lit carpet).
cv::Mat chromaPicture(const cv::Mat& bgr) {
  cv::Mat out(bgr.size(), CV_8UC3, cv::Scalar(0, 0, 0));
  for (int y = 0; y < bgr.rows; ++y) {
    const auto* in = bgr.ptr<cv::Vec3b>(y);
    auto* o = out.ptr<cv::Vec3b>(y);
    for (int x = 0; x < bgr.cols; ++x) {
      const int sum = in[x][0] + in[x][1] + in[x][2];
      if (sum < 6) continue;  // outside the camera's view: black
      for (int c = 0; c < 3; ++c) o[x][c] = cv::saturate_cast<uint8_t>(384.0 * in[x][c] / sum);
    }
  }
  return out;
}

}  // namespace

struct LayerPipelines::Slot {
  std::mutex mutex;  // one run at a time per camera; the others wait and share it
  std::optional<CpuPipeline> pipeline;
  CameraCalibration built_calibration;
  PipelineOptions built_options;
  bool have_run = false;
  std::chrono::steady_clock::time_point last_run;
  SnapshotSource run;  // frame, detection, calibration, grid, blobs of the last run
  bool fresh = false;
  // The grid pictures of the last run, made when first asked.
  cv::Mat rectified, chroma, gradient, score;
};

LayerPipelines::LayerPipelines() = default;
LayerPipelines::~LayerPipelines() = default;

LayerPipelines::Slot& LayerPipelines::slot(uint32_t camera_id) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto& s = slots_[camera_id];
  if (!s) s = std::make_unique<Slot>();
  return *s;
}

bool LayerPipelines::runIfDue(Slot& s, CameraFeed& feed, const FieldModel& field, std::string& why) {
  const auto now = std::chrono::steady_clock::now();
  if (s.have_run && now - s.last_run < std::chrono::duration<double>(1.0 / kRunsPerSecond)) {
    s.fresh = false;
    return true;
  }
  const std::string name = "camera " + std::to_string(feed.cameraId());
  CameraFeed::Setup setup;
  if (!feed.snapshot(2.0, s.run.frame, s.run.detection, s.fresh, &setup)) {
    why = name + " has processed no frame yet";
    return false;
  }
  if (!setup.known) {
    why = name + "'s processor has made no frame yet";
    return false;
  }
  PipelineOptions options = setup.pipeline;
  options.threads = 1;  // the HTTP thread alone: the cameras keep their cores
  options.coarse_search = false;  // every picture at the grid's full resolution
  if (!s.pipeline || setup.calibration != s.built_calibration ||
      !sameOptions(options, s.built_options)) {
    s.pipeline.reset();
    try {
      s.pipeline.emplace(CameraModel(setup.calibration), field, options);
    } catch (const InputError& e) {
      why = name + ": the console's pipeline cannot be built: " + e.what();
      return false;
    }
    s.built_calibration = setup.calibration;
    s.built_options = options;
  }
  if (!s.pipeline->process(s.run.frame.image, s.run.blobs)) {
    why = name + ": the console's pipeline refused the frame: " + s.pipeline->lastError();
    return false;
  }
  s.run.calibration = setup.calibration;
  s.run.grid = s.pipeline->grid();
  s.run.plane_height = s.pipeline->options().plane_height;
  s.rectified.release();
  s.chroma.release();
  s.gradient.release();
  s.score.release();
  s.have_run = true;
  s.last_run = now;
  return true;
}

bool LayerPipelines::take(CameraFeed& feed, const FieldModel& field, SnapshotBase base, SnapshotSource& out,
                          bool& fresh, std::string& why) {
  Slot& s = slot(feed.cameraId());
  std::lock_guard<std::mutex> lock(s.mutex);
  if (!runIfDue(s, feed, field, why)) return false;
  // The pictures read the pipeline's state of the last run, which stays
  // until the next run (under this lock).
  auto made = [](cv::Mat& m, auto make) -> const cv::Mat& {
    if (m.empty()) m = make();
    return m;
  };
  const CpuPipeline& p = *s.pipeline;
  cv::Mat picture;
  switch (base) {
    case SnapshotBase::Raw: break;
    case SnapshotBase::Rectified: picture = made(s.rectified, [&] { return p.debugRectified(); }); break;
    case SnapshotBase::Chroma:
      picture = made(s.chroma, [&] { return chromaPicture(made(s.rectified, [&] { return p.debugRectified(); })); });
      break;
    case SnapshotBase::Gradient: picture = made(s.gradient, [&] { return p.debugGradient(); }); break;
    case SnapshotBase::Score: picture = made(s.score, [&] { return p.debugScore(); }); break;
  }
  out.frame.image = s.run.frame.image.clone();
  out.frame.format = s.run.frame.format;
  out.frame.index = s.run.frame.index;
  out.detection.CopyFrom(s.run.detection);
  out.calibration = s.run.calibration;
  out.grid = s.run.grid;
  out.plane_height = s.run.plane_height;
  out.blobs = s.run.blobs;
  out.grid_picture = picture;  // shared, read only
  fresh = s.fresh;
  return true;
}

bool LayerPipelines::grid(CameraFeed& feed, const FieldModel& field, RectifiedGrid& grid, double& plane_height_mm,
                          std::string& why) {
  Slot& s = slot(feed.cameraId());
  std::lock_guard<std::mutex> lock(s.mutex);
  if (!runIfDue(s, feed, field, why)) return false;
  grid = *s.run.grid;
  plane_height_mm = s.run.plane_height;
  return true;
}

}  // namespace dv::app

#pragma once
// The camera page's pixel-stage layers (rectified, chroma, gradient, score,
// blobs) at no cost to the detection threads: their pipeline buffers are
// never read. Instead, on request and on the console's HTTP thread, a
// console-owned single-threaded CPU pipeline runs over the console's copy of
// the camera's newest frame. One pipeline per camera, built on the first
// request and rebuilt when the calibration or pipeline options the camera's
// processor uses change; at most kRunsPerSecond runs a second per camera,
// whatever the number of viewers: a request in between gets the last run.
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "app/console_image.h"

namespace dv::app {

class CameraFeed;

class LayerPipelines {
 public:
  static constexpr double kRunsPerSecond = 4;
  LayerPipelines();
  ~LayerPipelines();

  // The last run on camera `feed` (a new one when due) into `out`, with the
  // grid picture of `base` (none for Raw). False with `why` when no frame
  // came yet or the camera's pipeline cannot be built.
  bool take(CameraFeed& feed, const FieldModel& field, SnapshotBase base, SnapshotSource& out, bool& fresh,
            std::string& why);
  // The rectified grid of that camera's grid layers and the plane it lies on.
  bool grid(CameraFeed& feed, const FieldModel& field, RectifiedGrid& grid, double& plane_height_mm,
            std::string& why);

 private:
  struct Slot;
  Slot& slot(uint32_t camera_id);
  // Under the slot's lock: runs the pipeline when due; false with why.
  bool runIfDue(Slot& s, CameraFeed& feed, const FieldModel& field, std::string& why);
  std::mutex mutex_;
  std::map<uint32_t, std::unique_ptr<Slot>> slots_;
};

}  // namespace dv::app

#pragma once
// A camera of a synthetic scene as a live source (`synthetic://SCENE/ID`,
// SCENE `default` (the built-in scene of `run`), a preset name or a scene
// file): the scene's frames for that camera
// are rendered once at start and then delivered at the scene's frame rate,
// looping, with Unix time stamps and frame numbers that keep counting, so
// `serve` on synthetic cameras behaves as on real ones.
#include <string>
#include <vector>

#include "geometry/camera_model.h"
#include "geometry/geometry_io.h"
#include "io/camera_source.h"

namespace dv::app {

bool isSyntheticSpec(const std::string& spec);

class SyntheticCamera : public CameraSource {
 public:
  // Throws InputError naming the spec: malformed, unknown scene, no such camera id.
  // fps > 0: frames come at that rate instead of the scene's.
  explicit SyntheticCamera(const std::string& spec, double fps = 0);
  GrabStatus grab(Frame& f, double timeout_s, std::string& why) override;
  void interrupt() override { interrupted_ = true; }
  std::string describe() const override { return describe_; }
  bool live() const override { return true; }
  SourceCounters counters() const override { return counters_; }

  // The scene's field and every camera's calibration (a synthetic camera's geometry).
  const Geometry& geometry() const { return geometry_; }
  uint32_t cameraId() const { return camera_id_; }

 private:
  std::string describe_;
  Geometry geometry_;
  uint32_t camera_id_ = 0;
  std::vector<cv::Mat> frames_;
  PixelFormat format_ = PixelFormat::Bgr8;
  double period_s_ = 1.0 / 60;
  double start_ = 0;  // steady s of frame 0
  uint64_t next_ = 0;
  std::atomic<bool> interrupted_{false};
  SourceCounters counters_;
};

}  // namespace dv::app

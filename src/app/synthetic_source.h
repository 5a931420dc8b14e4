#pragma once
// The built-in synthetic scene as a frame source: frames in time order, and
// within a frame camera by camera, each with the scene's truth for it.
// (In app, not io: it needs the renderer, and io must not depend on synth.)
#include <vector>

#include "dotvision/ssl_detection.pb.h"
#include "io/frame_source.h"
#include "synth/renderer.h"

namespace dv::app {

// The pixel format of the frames `spec` renders (BGR or its Bayer layout).
PixelFormat sceneFormat(const SceneSpec& spec);

class SyntheticSource : public FrameSource {
 public:
  // camera_indices: indices into spec.cameras to render (all if empty).
  // Throws std::invalid_argument for a scene the renderer cannot draw.
  SyntheticSource(const SceneSpec& spec, std::vector<size_t> camera_indices);

  bool next(Frame& f) override;
  std::string describe() const override;
  long expectedCount() const override {
    return static_cast<long>(renderer_.spec().frames) * static_cast<long>(cameras_.size());
  }

  // Of the frame last returned by next(): which camera (index into the
  // scene's cameras) and what it truly shows.
  size_t cameraIndex() const { return cameras_[last_camera_]; }
  const ssl::SSL_DetectionFrame& truth() const { return truth_; }
  const Renderer& renderer() const { return renderer_; }

 private:
  Renderer renderer_;
  std::vector<size_t> cameras_;
  int frame_ = 0;
  size_t camera_ = 0;
  size_t last_camera_ = 0;
  ssl::SSL_DetectionFrame truth_;
};

}  // namespace dv::app

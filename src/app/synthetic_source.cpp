#include "app/synthetic_source.h"

namespace dv::app {

PixelFormat sceneFormat(const SceneSpec& spec) {
  if (!spec.bayer) return PixelFormat::Bgr8;
  switch (spec.bayer_layout) {
    case BayerLayout::RGGB: return PixelFormat::BayerRggb8;
    case BayerLayout::GRBG: return PixelFormat::BayerGrbg8;
    case BayerLayout::GBRG: return PixelFormat::BayerGbrg8;
    case BayerLayout::BGGR: return PixelFormat::BayerBggr8;
  }
  return PixelFormat::BayerRggb8;
}

SyntheticSource::SyntheticSource(const SceneSpec& spec, std::vector<size_t> camera_indices)
    : renderer_(spec), cameras_(std::move(camera_indices)) {
  if (cameras_.empty())
    for (size_t i = 0; i < spec.cameras.size(); ++i) cameras_.push_back(i);
}

bool SyntheticSource::next(Frame& f) {
  const SceneSpec& spec = renderer_.spec();
  if (frame_ >= spec.frames || cameras_.empty()) return false;
  RenderedFrame rendered = renderer_.render(frame_, cameras_[camera_]);
  f.image = rendered.image;
  f.format = sceneFormat(spec);
  f.index = static_cast<uint32_t>(frame_);
  f.t_capture = frame_ / spec.fps;
  f.name = "scene '" + spec.name + "' camera " +
           std::to_string(spec.cameras[cameras_[camera_]].calib.camera_id) + " frame " +
           std::to_string(frame_);
  truth_ = std::move(rendered.truth);
  last_camera_ = camera_;
  if (++camera_ == cameras_.size()) {
    camera_ = 0;
    ++frame_;
  }
  return true;
}

std::string SyntheticSource::describe() const {
  const SceneSpec& spec = renderer_.spec();
  return "synthetic scene '" + spec.name + "' (" + std::to_string(spec.frames) + " frames)";
}

}  // namespace dv::app

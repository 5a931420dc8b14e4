#include "app/synthetic_camera.h"


#include <algorithm>
#include <chrono>
#include <thread>

#include "app/synthetic_source.h"
#include "core/clock.h"
#include "core/error.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv::app {

namespace {
constexpr const char* kPrefix = "synthetic://";
constexpr int kMaxLoopFrames = 120;  // frames rendered at start (memory: 5 MB each at 2448x2048)

}  // namespace

bool isSyntheticSpec(const std::string& spec) { return spec.rfind(kPrefix, 0) == 0; }

SyntheticCamera::SyntheticCamera(const std::string& spec, double fps) : describe_(spec) {
  const std::string rest = spec.substr(std::string(kPrefix).size());
  const size_t slash = rest.rfind('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == rest.size())
    throw InputError(spec, "expected synthetic://SCENE/CAMERA_ID (SCENE: a preset name or a scene file)");
  const std::string scene = rest.substr(0, slash), id_text = rest.substr(slash + 1);
  if (!std::all_of(id_text.begin(), id_text.end(), [](unsigned char c) { return std::isdigit(c); }))
    throw InputError(spec, "camera id '" + id_text + "' is not a number");
  camera_id_ = static_cast<uint32_t>(std::stoul(id_text));
  SceneSpec s = scene == "default" ? defaultScene()  // the built-in field of `dotvision run`
               : (scene.find('/') != std::string::npos || scene.find('.') != std::string::npos)
                   ? loadScene(scene)
                   : presetScene(scene);
  s.frames = std::min(s.frames, kMaxLoopFrames);
  size_t index = s.cameras.size();
  std::string ids;
  for (size_t i = 0; i < s.cameras.size(); ++i) {
    ids += (ids.empty() ? "" : ", ") + std::to_string(s.cameras[i].calib.camera_id);
    if (s.cameras[i].calib.camera_id == camera_id_) index = i;
  }
  if (index == s.cameras.size())
    throw InputError(spec, "scene '" + s.name + "' has no camera " + id_text + " (cameras: " + ids + ")");
  SyntheticSource source(s, {index});
  geometry_ = source.renderer().geometry();
  format_ = sceneFormat(s);
  if (fps > 0) s.fps = fps;
  period_s_ = 1.0 / s.fps;
  Frame f;
  while (source.next(f)) frames_.push_back(f.image.clone());
  describe_ = spec + " (" + std::to_string(frames_.size()) + " frames looped at " +
              std::to_string(static_cast<int>(s.fps + 0.5)) + " fps)";
}

GrabStatus SyntheticCamera::grab(Frame& f, double timeout_s, std::string& why) {
  if (frames_.empty()) {
    why = "the scene rendered no frames";
    return GrabStatus::End;
  }
  if (start_ == 0) start_ = steadySeconds();
  const double due = start_ + static_cast<double>(next_) * period_s_;
  const double deadline = steadySeconds() + timeout_s;
  while (steadySeconds() < due) {
    if (interrupted_.exchange(false) || steadySeconds() >= deadline) return GrabStatus::Timeout;
    std::this_thread::sleep_for(std::chrono::duration<double>(std::min(0.002, due - steadySeconds())));
  }
  // Behind schedule (a slow consumer does not slow a camera): skip to now.
  const uint64_t now_index = static_cast<uint64_t>((steadySeconds() - start_) / period_s_);
  if (now_index > next_ + 1) {
    counters_.lost_frames += now_index - next_;
    next_ = now_index;
  }
  frames_[next_ % frames_.size()].copyTo(f.image);
  f.format = format_;
  f.t_arrival = unixSeconds();
  f.t_capture = f.t_arrival;
  f.t_capture_camera = static_cast<double>(next_) * period_s_;
  f.index = static_cast<uint32_t>(next_);
  f.name = "camera " + std::to_string(camera_id_) + " frame " + std::to_string(next_);
  ++next_;
  ++counters_.frames;
  return GrabStatus::Frame;
}

}  // namespace dv::app

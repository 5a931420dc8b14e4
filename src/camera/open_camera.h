#pragma once
// One entry point from a `--source` text (or a site config's `source:`) to a
// CameraSource: GenICam cameras (`genicam://ID`), V4L2 devices
// (`v4l2:///dev/video0`, `/dev/videoN`), network streams (`rtsp://`,
// `http://`, `https://`), else files, directories, globs and videos.
#include <memory>
#include <string>
#include <vector>

#include "io/camera_source.h"
#include "io/frame_source.h"

namespace dv {

struct CameraSourceOptions {
  FrameSourceOptions files;  // fps, Bayer layout of gray images, time origin, scene camera
  bool realtime = false;     // files and videos: paced at their own frame rate
  std::vector<CameraSetting> settings;  // applied in order once the camera is open
};

// True when `spec` names a camera or a network stream rather than files.
bool isCameraSpec(const std::string& spec);

// Opens `spec` and applies options.settings (the read-back lines go to
// `settings_report` when given). Throws InputError naming the source: no
// such camera (with the ids present), a refused setting, a Mono8 camera...
std::unique_ptr<CameraSource> openCameraSource(const std::string& spec, const CameraSourceOptions& options,
                                               std::vector<std::string>* settings_report = nullptr);

}  // namespace dv

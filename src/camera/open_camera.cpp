#include "camera/open_camera.h"

#include "camera/genicam_source.h"
#include "camera/stream_source.h"
#include "core/error.h"

namespace dv {

namespace {
bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }
}  // namespace

bool isCameraSpec(const std::string& spec) {
  return startsWith(spec, "genicam://") || startsWith(spec, "v4l2://") || startsWith(spec, "/dev/video") ||
         startsWith(spec, "rtsp://") || startsWith(spec, "http://") || startsWith(spec, "https://");
}

std::unique_ptr<CameraSource> openCameraSource(const std::string& spec, const CameraSourceOptions& options,
                                               std::vector<std::string>* settings_report) {
  std::unique_ptr<CameraSource> source;
  if (startsWith(spec, "genicam://")) {
    source = std::make_unique<GenicamSource>(spec.substr(10));
  } else if (isStreamSpec(spec)) {
    source = std::make_unique<StreamSource>(spec);
  } else {
    source = std::make_unique<FileCameraSource>(openFrameSource(spec, options.files), options.realtime);
  }
  auto lines = source->applySettings(options.settings);
  if (settings_report) *settings_report = std::move(lines);
  return source;
}

}  // namespace dv

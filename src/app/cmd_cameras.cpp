// `dotvision cameras`: what is attached. GenICam cameras (GigE Vision,
// USB3 Vision) with the id to give as --source genicam://ID, their
// interface, current pixel format and size; then V4L2 devices.
#include <cstdio>
#include <vector>

#include "app/commands.h"
#include "camera/camera_list.h"
#include "camera/v4l2_list.h"

namespace dv::app {

namespace {

void printGenicam(const std::vector<GenicamCameraInfo>& cams) {
  if (cams.empty()) {
    std::printf("GenICam cameras: none (%s).\n", genicamEmptyListHint().c_str());
    return;
  }
  std::printf("GenICam cameras (%zu):\n", cams.size());
  for (const auto& c : cams) {
    std::printf("  genicam://%s\n", c.id.c_str());
    std::printf("    %s %s, serial %s, %s\n", c.vendor.c_str(), c.model.c_str(), c.serial.c_str(),
                c.interfaceText().c_str());
    if (!c.pixel_format.empty()) std::printf("    %s %dx%d\n", c.pixel_format.c_str(), c.width, c.height);
    if (!c.problem.empty()) std::printf("    (%s)\n", c.problem.c_str());
  }
}

void printV4l2(const std::vector<V4l2Device>& devices) {
  if (devices.empty()) {
    std::printf("V4L2 devices: none (no /dev/video* capture device; a webcam may need its driver "
                "or membership of the 'video' group).\n");
    return;
  }
  std::printf("V4L2 devices (%zu):\n", devices.size());
  for (const auto& d : devices) {
    std::printf("  v4l2://%s  %s\n", d.path.c_str(), d.name.c_str());
    std::string formats;
    for (const auto& f : d.formats) formats += (formats.empty() ? "" : ", ") + f;
    if (!formats.empty()) std::printf("    %s\n", formats.c_str());
  }
}

}  // namespace

CommandFn addCamerasCommand(CLI::App& root) {
  root.add_subcommand("cameras",
                      "List attached cameras: GenICam (GigE Vision / USB3 Vision) with their ids for "
                      "--source genicam://ID, interface, pixel format and size; V4L2 devices.");
  return [] {
    printGenicam(listGenicamCameras(true));
    printV4l2(listV4l2Devices());
    return kExitOk;
  };
}

}  // namespace dv::app

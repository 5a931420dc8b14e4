#include "app/console_host.h"

#include "app/camera_runner.h"
#include "app/packet_outputs.h"

namespace dv::app {

std::vector<std::string> useCalibration(CameraRunner& runner, Geometry& geometry, PacketOutputs& outputs,
                                        const CameraCalibration& c) {
  std::vector<std::string> notes;
  runner.setCalibration(c);
  notes.push_back("camera " + std::to_string(c.camera_id) + ": its processor uses the new calibration from the next frame");
  for (CameraCalibration& old : geometry.cameras)
    if (old.camera_id == c.camera_id) old = c;
  outputs.setGeometry(toProto(geometry));
  if (outputs.publishesGeometry()) notes.push_back("the published geometry has the new calibration");
  return notes;
}

}  // namespace dv::app

#pragma once
// What the console needs of the process hosting it: serve's SiteRuntime, or
// run's single camera (cmd_run). All of it is called on the host's main loop
// (ConsoleServer::service) or before the cameras start, never from the
// console's HTTP threads.
#include <string>
#include <vector>

#include "app/site_config.h"
#include "geometry/geometry_io.h"

namespace dv::app {

class CameraRunner;
class PacketOutputs;

class ConsoleHost {
 public:
  virtual ~ConsoleHost() = default;
  // The config the console shows and edits; an empty `path`: none (no
  // config can be changed or saved).
  virtual const SiteConfig& config() const = 0;
  virtual const Geometry& geometry() const = 0;
  virtual size_t cameraCount() const = 0;
  virtual CameraRunner& runner(size_t i) = 0;
  // A validated new config: what was applied and what was not.
  virtual std::vector<std::string> reload(const SiteConfig& next) = 0;
  // An accepted calibration (see SiteRuntime::setCalibration). Throws
  // InputError when no camera of that id runs or `publisher` is bad.
  virtual std::vector<std::string> setCalibration(const CameraCalibration& c, const std::string& publisher) = 0;
};

// What either host does with an accepted calibration of `runner`'s camera:
// the processor is rebuilt with it at the next frame, and `geometry` and
// what `outputs` publish have it. Returns the notes for the operator.
std::vector<std::string> useCalibration(CameraRunner& runner, Geometry& geometry, PacketOutputs& outputs,
                                        const CameraCalibration& c);

}  // namespace dv::app

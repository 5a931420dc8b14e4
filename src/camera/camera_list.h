#pragma once
// The GenICam cameras Aravis can see (GigE Vision discovery on every
// interface, USB3 Vision enumeration), for `dotvision cameras` and for
// resolving `genicam://ID`.
#include <string>
#include <vector>

namespace dv {

struct GenicamCameraInfo {
  std::string id;         // Aravis device id ("Aravis-Fake-GV01"): genicam://<id>
  std::string vendor, model, serial;
  std::string protocol;   // "GigEVision", "USB3Vision"
  std::string address;    // GigE: IP address; USB: bus address (may be empty)
  std::string physical_id;  // GigE: MAC address; USB: the device's unique id
  // Read from the camera itself (only with details); empty / 0 where the
  // camera could not be opened, and then `problem` says why.
  std::string pixel_format;
  int width = 0, height = 0;
  std::string problem;

  // "GigE 192.168.1.10" or "USB3 ...".
  std::string interfaceText() const;
};

// Discovers the cameras present (about a second: GigE discovery waits for
// answers). With `details`, opens each one briefly for its pixel format and
// size.
std::vector<GenicamCameraInfo> listGenicamCameras(bool details);

// Why a camera list may be empty, as one line (no camera, permissions,
// firewall for GigE Vision discovery on UDP 3956).
std::string genicamEmptyListHint();

// The Aravis device id of the camera `wanted` names: its device id, serial
// number, GigE address or physical (MAC) id; "" for the only camera
// present. Throws InputError(source, ...) when none or several match,
// listing the cameras present.
std::string resolveGenicamId(const std::string& wanted, const std::string& source);

// True when discovery finds the camera with Aravis device id `device_id`.
bool genicamCameraPresent(const std::string& device_id);

}  // namespace dv

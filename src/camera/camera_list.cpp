#include "camera/camera_list.h"

#include <arv.h>

#include "core/error.h"

namespace dv {

namespace {

std::string text(const char* s) { return s ? s : ""; }

std::vector<GenicamCameraInfo> discover() {
  arv_update_device_list();
  std::vector<GenicamCameraInfo> out;
  const unsigned n = arv_get_n_devices();
  for (unsigned i = 0; i < n; ++i) {
    GenicamCameraInfo c;
    c.id = text(arv_get_device_id(i));
    c.vendor = text(arv_get_device_vendor(i));
    c.model = text(arv_get_device_model(i));
    c.serial = text(arv_get_device_serial_nbr(i));
    c.protocol = text(arv_get_device_protocol(i));
    c.address = text(arv_get_device_address(i));
    c.physical_id = text(arv_get_device_physical_id(i));
    out.push_back(std::move(c));
  }
  return out;
}

void readDetails(GenicamCameraInfo& c) {
  GError* error = nullptr;
  ArvCamera* camera = arv_camera_new(c.id.c_str(), &error);
  if (!camera) {
    c.problem = std::string("cannot open: ") + (error ? error->message : "unknown error");
    g_clear_error(&error);
    return;
  }
  const char* format = arv_camera_get_pixel_format_as_string(camera, &error);
  if (format) c.pixel_format = format;
  g_clear_error(&error);
  gint x = 0, y = 0;
  arv_camera_get_region(camera, &x, &y, &c.width, &c.height, &error);
  if (error) c.problem = std::string("cannot read the image size: ") + error->message;
  g_clear_error(&error);
  g_object_unref(camera);
}

std::string listText(const std::vector<GenicamCameraInfo>& cams) {
  std::string out;
  for (const auto& c : cams) {
    if (!out.empty()) out += "; ";
    out += c.id + " (serial " + c.serial + ", " + c.interfaceText() + ")";
  }
  return out;
}

}  // namespace

std::string GenicamCameraInfo::interfaceText() const {
  if (protocol == "GigEVision") return "GigE " + address;
  if (protocol == "USB3Vision") return address.empty() ? "USB3" : "USB3 " + address;
  return protocol + (address.empty() ? "" : " " + address);
}

std::vector<GenicamCameraInfo> listGenicamCameras(bool details) {
  auto cams = discover();
  if (details)
    for (auto& c : cams) readDetails(c);
  return cams;
}

std::string genicamEmptyListHint() {
  return "no GenICam camera answered: is one connected and powered? A USB3 Vision camera needs read/write "
         "permission on its USB device (a udev rule or group); GigE Vision discovery needs the camera on a "
         "directly reachable subnet and a firewall that lets UDP port 3956 through (the replies come from "
         "the camera's address)";
}

std::string resolveGenicamId(const std::string& wanted, const std::string& source) {
  const auto cams = discover();
  if (cams.empty()) throw InputError(source, genicamEmptyListHint());
  if (wanted.empty()) {
    if (cams.size() == 1) return cams.front().id;
    throw InputError(source, "several GenICam cameras are present; name one with genicam://ID: " +
                                 listText(cams));
  }
  for (const auto& c : cams)
    if (c.id == wanted) return c.id;
  std::vector<GenicamCameraInfo> matches;
  for (const auto& c : cams)
    if (c.serial == wanted || (!c.address.empty() && c.address == wanted) ||
        (!c.physical_id.empty() && c.physical_id == wanted))
      matches.push_back(c);
  if (matches.size() == 1) return matches.front().id;
  if (matches.size() > 1)
    throw InputError(source, "'" + wanted + "' matches several cameras; use the device id: " + listText(matches));
  throw InputError(source, "no GenICam camera '" + wanted + "' (by device id, serial, address or MAC); present: " +
                               listText(cams));
}

bool genicamCameraPresent(const std::string& device_id) {
  for (const auto& c : discover())
    if (c.id == device_id) return true;
  return false;
}

}  // namespace dv

#include "camera/genicam_defaults.h"

#include <arv.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>

#include "camera/genicam_pixels.h"
#include "camera/aravis_error.h"
#include "core/error.h"

namespace dv {

namespace {

// Keeps the camera's format if usable, else switches to its best color
// format; returns a note when it switched.
std::string choosePixelFormat(ArvCamera* camera, const std::string& spec, const std::string& camera_text) {
  GError* error = nullptr;
  const ArvPixelFormat current = arv_camera_get_pixel_format(camera, &error);
  if (error) throw InputError(spec, camera_text + ": cannot read PixelFormat: " + takeErrorMessage(error));
  if (genicamPixelLayout(current)) return {};
  const char* current_name = arv_camera_get_pixel_format_as_string(camera, nullptr);
  guint n = 0, n_names = 0;
  gint64* formats = arv_camera_dup_available_pixel_formats(camera, &n, nullptr);
  const char** names = arv_camera_dup_available_pixel_formats_as_strings(camera, &n_names, nullptr);
  int best = -1, best_rank = 0;
  std::string offered;
  for (guint i = 0; formats && i < n; ++i) {
    const int rank = genicamFormatPreference(static_cast<uint32_t>(formats[i]));
    if (rank > best_rank) best = static_cast<int>(i), best_rank = rank;
    if (names && i < n_names) offered += (offered.empty() ? "" : ", ") + std::string(names[i]);
  }
  const ArvPixelFormat chosen = best >= 0 ? static_cast<ArvPixelFormat>(formats[best]) : 0;
  g_free(formats);
  g_free(names);
  const std::string reason = unusablePixelFormatReason(current, current_name ? current_name : "?");
  if (best < 0)
    throw InputError(spec, camera_text + ": " + reason + "; the camera offers only: " + offered);
  arv_camera_set_pixel_format(camera, chosen, &error);
  if (error) throw InputError(spec, camera_text + ": cannot switch PixelFormat: " + takeErrorMessage(error));
  const char* name = arv_camera_get_pixel_format_as_string(camera, nullptr);
  return std::string("PixelFormat ") + (name ? name : "?") + " (the camera was in " +
         (current_name ? current_name : "?") + ")";
}

}  // namespace

std::vector<std::string> applyGenicamDefaults(ArvCamera* camera, double max_fps, const std::string& spec,
                                              const std::string& camera_text) {
  GError* error = nullptr;
  std::vector<std::string> notes;
  if (arv_camera_is_feature_available(camera, "AcquisitionMode", nullptr)) {
    arv_camera_set_acquisition_mode(camera, ARV_ACQUISITION_MODE_CONTINUOUS, &error);
    notes.push_back(error ? "AcquisitionMode not set: " + takeErrorMessage(error) : "continuous acquisition");
  }
  // Auto exposure and auto gain make the colors flicker from frame to frame.
  if (arv_camera_is_exposure_auto_available(camera, nullptr)) {
    arv_camera_set_exposure_time_auto(camera, ARV_AUTO_OFF, &error);
    notes.push_back(error ? "ExposureAuto not set: " + takeErrorMessage(error) : "ExposureAuto Off");
  }
  if (arv_camera_is_gain_auto_available(camera, nullptr)) {
    arv_camera_set_gain_auto(camera, ARV_AUTO_OFF, &error);
    notes.push_back(error ? "GainAuto not set: " + takeErrorMessage(error) : "GainAuto Off");
  }
  if (auto chosen = choosePixelFormat(camera, spec, camera_text); !chosen.empty()) notes.push_back(chosen);
  if (const double fps = applyGenicamFrameRateDefault(camera, max_fps, spec); fps > 0) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g fps", fps);
    notes.push_back(text);
  }
  if (arv_camera_is_gv_device(camera)) {
    const guint size = arv_camera_gv_auto_packet_size(camera, &error);
    notes.push_back(error ? "packet size not negotiated: " + takeErrorMessage(error)
                          : "packet size " + std::to_string(size));
  }
  return notes;
}

double applyGenicamFrameRateDefault(ArvCamera* camera, double max_fps, const std::string& spec) {
  GError* error = nullptr;
  if (!arv_camera_is_frame_rate_available(camera, nullptr)) return -1;
  double lo = 0, hi = 0;
  arv_camera_get_frame_rate_bounds(camera, &lo, &hi, &error);
  if (error || hi <= 0) {
    g_clear_error(&error);
    return -1;
  }
  arv_camera_set_frame_rate(camera, std::clamp(max_fps, lo, hi), &error);
  if (error) {
    spdlog::warn("{}: frame rate not set: {}", spec, takeErrorMessage(error));
    return -1;
  }
  return arv_camera_get_frame_rate(camera, nullptr);
}

}  // namespace dv

#pragma once
// Start-up defaults for a GenICam camera, before any --camera-set:
// continuous acquisition, auto exposure and auto gain off (they make the
// colors flicker), a usable color pixel format, the camera's maximum frame
// rate up to a cap, and for GigE a packet size negotiated for the link.
#include <string>
#include <vector>

typedef struct _ArvCamera ArvCamera;

namespace dv {

// Applies the defaults; returns what was done, one note each. Throws
// InputError(source, ...) naming `camera_text` when the camera offers no
// color format (monochrome only) or its format cannot be read or changed.
std::vector<std::string> applyGenicamDefaults(ArvCamera* camera, double max_fps, const std::string& source,
                                              const std::string& camera_text);

// The frame rate default alone: the camera's maximum, at most max_fps (for
// after a size or format change). Returns the rate set, -1 where the
// camera has no settable frame rate.
double applyGenicamFrameRateDefault(ArvCamera* camera, double max_fps, const std::string& source);

}  // namespace dv

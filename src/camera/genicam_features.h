#pragma once
// GenICam features by name on an open Aravis device: set one from text and
// read it back, with one clear message for an unknown feature or a value
// the camera refuses.
#include <string>

#include "io/camera_source.h"

typedef struct _ArvDevice ArvDevice;

namespace dv {

// Sets `s` on `device` and returns the value read back as one line
// ("ExposureTime = 4000 (us)"; "... (asked 4001)" where the camera adjusted
// it). Throws InputError(source, ...) naming the feature and `camera`
// (e.g. "Aravis Fake, serial GV01") for an unknown, unavailable or
// read-only feature, a value that does not parse, is out of range or is
// refused by the camera.
std::string setGenicamFeature(ArvDevice* device, const CameraSetting& s, const std::string& source,
                              const std::string& camera);

// The current value of feature `name` as text ("" when it has none).
std::string genicamFeatureText(ArvDevice* device, const char* name);

}  // namespace dv

// Geometry files in canonical JSON (src/geometry/geometry_io.cpp).
#include "fuzz_input.h"
#include "geometry/geometry_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  dv::fuzz::expectOnlyInputErrors([&] { dv::geometryFromJson(dv::fuzz::text(data, size), "fuzz.json"); });
  return 0;
}

// Geometry files in YAML (src/geometry/geometry_io.cpp).
#include "fuzz_input.h"
#include "geometry/geometry_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  dv::fuzz::expectOnlyInputErrors([&] { dv::geometryFromYaml(dv::fuzz::text(data, size), "fuzz.yaml"); });
  return 0;
}

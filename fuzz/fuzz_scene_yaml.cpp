// Synthetic scene descriptions (src/synth/scene_yaml.cpp).
#include "fuzz_input.h"
#include "synth/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  dv::fuzz::expectOnlyInputErrors([&] { dv::sceneFromYaml(dv::fuzz::text(data, size), "fuzz.yaml"); });
  return 0;
}

// The site configuration `serve` reads (src/app/site_config.cpp).
#include "app/site_config.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  dv::fuzz::expectOnlyInputErrors([&] { dv::app::parseSiteConfig(dv::fuzz::text(data, size), "fuzz.yaml"); });
  return 0;
}

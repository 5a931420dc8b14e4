// Detection files for `eval`: JSONL or SSL log, told apart by their first
// bytes (src/eval/detection_files.cpp), and ground-truth JSONL.
#include "eval/detection_files.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = dv::fuzz::inputFile(data, size, "fuzz.jsonl");
  dv::fuzz::expectOnlyInputErrors([&] { dv::readDetectionFile(path); });
  dv::fuzz::expectOnlyInputErrors([&] { dv::readTruthJsonl(path); });
  return 0;
}

#pragma once
// Helpers shared by the fuzz targets: the readers under test that take a
// path get the input through a per-process file.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"

namespace dv::fuzz {

// Writes `data` to a file named `name` (its extension picks the reader) in a
// per-process folder under $TMPDIR and returns its path.
inline std::string inputFile(const uint8_t* data, size_t size, const std::string& name) {
  static const std::string dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string d = std::string(tmp && *tmp ? tmp : "/tmp") + "/dv_fuzz_" + std::to_string(::getpid());
    std::string cmd = "mkdir -p '" + d + "'";
    if (std::system(cmd.c_str()) != 0) std::abort();
    return d;
  }();
  const std::string path = dir + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

inline std::string text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Runs `parse`; an InputError is the expected answer to bad input, anything
// else escapes and is reported by libFuzzer as a crash.
template <typename Fn>
void expectOnlyInputErrors(Fn&& parse) {
  try {
    parse();
  } catch (const dv::InputError&) {
  }
}

}  // namespace dv::fuzz

#pragma once
// Helpers shared by the fuzz targets: the readers under test that take a
// path get the input through a per-process file.
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/error.h"

namespace dv::fuzz {

// Writes `data` to a file named `name` (its extension picks the reader) in a
// per-process folder under $TMPDIR, else /dev/shm, else /tmp, and returns its
// path. Memory-backed by default: ext4 flushes a file rewritten with O_TRUNC
// when it is closed, which would make every run wait for the disk.
inline char g_input_dir[4096];  // a plain buffer: still valid in the atexit handler

inline void removeInputDir() {
  std::error_code ec;
  std::filesystem::remove_all(g_input_dir, ec);
}

inline std::string inputFile(const uint8_t* data, size_t size, const std::string& name) {
  static const std::string dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    const std::string base = tmp && *tmp ? tmp : ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    std::string d = base + "/dv_fuzz_" + std::to_string(::getpid());
    if (d.size() >= sizeof g_input_dir || (::mkdir(d.c_str(), 0700) != 0 && errno != EEXIST)) std::abort();
    std::snprintf(g_input_dir, sizeof g_input_dir, "%s", d.c_str());
    std::atexit(removeInputDir);
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

#include "io/frame_times.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace dv {

std::string frameTimesLine(const std::string& file, const FrameTiming& t) {
  char buf[96];
  std::snprintf(buf, sizeof buf, ",%u,%.17g,%s", t.index, t.t_capture, pixelFormatName(t.format));
  return file + buf;
}

std::map<std::string, FrameTiming> readFrameTimes(const std::string& dir) {
  std::map<std::string, FrameTiming> out;
  const std::string path = (std::filesystem::path(dir) / kFrameTimesFile).string();
  std::ifstream in(path);
  if (!in) return out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || (n == 1 && line == kFrameTimesHeader)) continue;
    std::stringstream ss(line);
    std::string file, index, t, format;
    const auto bad = [&](const std::string& what) {
      return InputError(path + ":" + std::to_string(n), what + " (expected " + kFrameTimesHeader + ")");
    };
    if (!std::getline(ss, file, ',') || !std::getline(ss, index, ',') || !std::getline(ss, t, ',') ||
        !std::getline(ss, format))
      throw bad("too few fields");
    FrameTiming ft;
    try {
      size_t used = 0;
      const unsigned long i = std::stoul(index, &used);
      if (used != index.size() || i > UINT32_MAX) throw bad("index '" + index + "' is not a frame number");
      ft.index = static_cast<uint32_t>(i);
      ft.t_capture = std::stod(t, &used);
      if (used != t.size()) throw bad("t_capture '" + t + "' is not a number");
    } catch (const std::logic_error&) {
      throw bad("index or t_capture is not a number");
    }
    if (format == "bgr8") ft.format = PixelFormat::Bgr8;
    else ft.format = bayerFormatFromName(format.rfind("bayer-", 0) == 0 ? format.substr(6, 4) : format,
                                         path + ":" + std::to_string(n));
    out[file] = ft;
  }
  return out;
}

}  // namespace dv

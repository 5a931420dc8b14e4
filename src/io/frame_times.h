#pragma once
// frame_times.csv beside a folder of frames: each frame's number, capture
// time (Unix s) and pixel format as a camera delivered it, so that `run`
// on a raw dump processes the frames with the very time stamps (the
// tracker's input) and layouts they had live.
#include <cstdint>
#include <map>
#include <string>

#include "io/frame_source.h"

namespace dv {

inline constexpr const char* kFrameTimesFile = "frame_times.csv";
inline constexpr const char* kFrameTimesHeader = "file,index,t_capture,format";

// One line (without newline) for `file` (a name inside the folder).
std::string frameTimesLine(const std::string& file, const FrameTiming& t);
// The table of `dir`/frame_times.csv by file name; empty when there is none.
// Throws InputError naming the file and line for a malformed line.
std::map<std::string, FrameTiming> readFrameTimes(const std::string& dir);

}  // namespace dv

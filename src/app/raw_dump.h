#pragma once
// A bug report from the raw rings: each camera's last seconds of frames
// (frame_<camera>_<number>.pgm for Bayer mosaics, .png for color), their
// numbers, times and layouts (frame_times.csv), the detection packets sent
// for them (detections.jsonl) and the geometry (geometry.json), in one new
// folder. `dotvision run --source DIR --geometry DIR/geometry.json
// --camera-id N` processes the same frames with the same time stamps.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "geometry/geometry_io.h"
#include "live/raw_ring.h"

namespace dv::app {

struct RawDumpCamera {
  uint32_t camera_id = 0;
  std::vector<RawRing::Entry> frames;
};

// Writes into `dir` (created; must not hold a dump already). Returns the
// number of frames written. Throws InputError naming the file that failed.
size_t writeRawDump(const std::string& dir, const std::vector<RawDumpCamera>& cameras, const Geometry& geometry);

}  // namespace dv::app

#include "app/raw_dump.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "dotvision/ssl_wrapper.pb.h"
#include "geometry/proto_json.h"
#include "io/frame_times.h"

namespace dv::app {

namespace fs = std::filesystem;

size_t writeRawDump(const std::string& dir, const std::vector<RawDumpCamera>& cameras, const Geometry& geometry) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot create the folder: " + ec.message());
  if (fs::exists(fs::path(dir) / kFrameTimesFile)) throw InputError(dir, "already holds a raw dump");
  saveGeometry(geometry, (fs::path(dir) / "geometry.json").string());
  std::ofstream times(fs::path(dir) / kFrameTimesFile), detections(fs::path(dir) / "detections.jsonl");
  times << kFrameTimesHeader << '\n';
  size_t written = 0;
  for (const RawDumpCamera& cam : cameras) {
    for (const RawRing::Entry& e : cam.frames) {
      char name[64];
      std::snprintf(name, sizeof name, "frame_%u_%06u.%s", cam.camera_id, e.index,
                    e.format == PixelFormat::Bgr8 ? "png" : "pgm");
      const std::string path = (fs::path(dir) / name).string();
      if (!cv::imwrite(path, e.image)) throw InputError(path, "cannot write the frame");
      times << frameTimesLine(name, {e.index, e.t_capture, e.format}) << '\n';
      ssl::SSL_WrapperPacket packet;
      if (packet.ParseFromString(e.packet)) detections << toCanonicalJson(packet) << '\n';
      ++written;
    }
  }
  times.close();
  detections.close();
  if (!times || !detections) throw InputError(dir, "writing frame_times.csv or detections.jsonl failed");
  return written;
}

}  // namespace dv::app

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "geometry/proto_json.h"
#include "synth/renderer.h"

namespace dv {

namespace {

std::string frameName(const std::string& dir, uint32_t camera_id, int frame, const char* ext) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%u_%05d.%s", camera_id, frame, ext);
  return (std::filesystem::path(dir) / name).string();
}

void writeImage(const std::string& path, const cv::Mat& image, const std::string& out_dir) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw InputError(out_dir, "cannot write " + path + ": " + e.what());
  }
  if (!ok) throw InputError(out_dir, "cannot write " + path);
}

}  // namespace

void writeScene(const SceneSpec& spec, const std::string& out_dir) {
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec || !std::filesystem::is_directory(out_dir))
    throw InputError(out_dir, "cannot create the output directory: " + ec.message());
  const Renderer renderer(spec);
  saveGeometry(renderer.geometry(), (std::filesystem::path(out_dir) / "geometry.json").string());
  const std::string truth_path = (std::filesystem::path(out_dir) / "truth.jsonl").string();
  std::ofstream truth(truth_path, std::ios::trunc);
  if (!truth) throw InputError(out_dir, "cannot write " + truth_path);
  for (int frame = 0; frame < spec.frames; ++frame) {
    for (size_t c = 0; c < spec.cameras.size(); ++c) {
      const RenderedFrame f = renderer.render(frame, c);
      const uint32_t id = spec.cameras[c].calib.camera_id;
      if (spec.bayer) writeImage(frameName(out_dir, id, frame, "pgm"), f.image, out_dir);
      if (!f.jpeg.empty()) {
        const std::string path = frameName(out_dir, id, frame, "jpg");
        std::ofstream jpg(path, std::ios::binary | std::ios::trunc);
        jpg.write(reinterpret_cast<const char*>(f.jpeg.data()), static_cast<std::streamsize>(f.jpeg.size()));
        if (!jpg) throw InputError(out_dir, "cannot write " + path);
      } else if (spec.write_png || !spec.bayer)
        writeImage(frameName(out_dir, id, frame, "png"), spec.bayer ? f.rgb : f.image, out_dir);
      truth << toCanonicalJson(f.truth) << '\n';
    }
  }
  truth.flush();
  if (!truth) throw InputError(out_dir, "cannot write " + truth_path);
}

}  // namespace dv

#pragma once
// Ray-casting renderer of SSL scenes: every sample is a ray through the
// league camera model (CameraModel::pixelRay, the exact inverse of the
// distortion), so a rendered object lies where the camera model projects it.
// Pixel centers are at integer coordinates; each Bayer pixel is sampled at
// its own center, so the mosaic is physically right.
#include <opencv2/core.hpp>
#include <memory>
#include <string>
#include <vector>

#include "dotvision/ssl_detection.pb.h"
#include "geometry/geometry_io.h"
#include "synth/scene.h"

namespace dv {

struct RenderedFrame {
  // CV_8UC1 Bayer RGGB (R at even row / even column) when spec.bayer, else
  // CV_8UC3 BGR.
  cv::Mat image;
  // CV_8UC3 BGR of the same exposure, filled only when spec.bayer and
  // spec.write_png are both set (image is then the Bayer mosaic).
  cv::Mat rgb;
  // The JPEG file `image` was decoded from, when spec.jpeg_quality is set.
  std::vector<uchar> jpeg;
  // What the camera sees, by construction: camera_id, frame_number (from 0),
  // t_capture = t_sent = frame / fps, robots and ball whose projected center
  // lies inside the image. Robots: x/y of the center blob, pixel_x/y its
  // projection at the robot height, orientation, height, confidence 1.
  // Ball: x/y/z of its center, pixel_x/y its projection, area 0.
  // Positions are those at the middle of the exposure.
  dv::ssl::SSL_DetectionFrame truth;
};

class Renderer {
 public:
  // Throws std::invalid_argument for scenes it cannot render (no camera,
  // image size 0, antialias < 1, ...). Precomputes the carpet texture.
  explicit Renderer(const SceneSpec& spec);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const SceneSpec& spec() const { return spec_; }
  // The field and the true calibrations of all cameras.
  Geometry geometry() const;
  // Frame `frame` (0-based) of camera `camera_index` (index into spec.cameras).
  RenderedFrame render(int frame, size_t camera_index) const;
  // Only the truth of that frame (cheap).
  dv::ssl::SSL_DetectionFrame truth(int frame, size_t camera_index) const;
  // Linear RGB radiance (CV_32FC3, B,G,R order) of one instant, before
  // lighting gains, blur, noise and mosaic. For tests and debugging.
  cv::Mat renderRadiance(double t, size_t camera_index) const;

 private:
  struct Impl;
  SceneSpec spec_;
  std::unique_ptr<Impl> impl_;
};

// Renders all frames of all cameras into out_dir (created if missing):
// frame_<cam>_<NNNNN>.pgm (Bayer) and/or .png (RGB), geometry.json (canonical
// JSON SSL_GeometryData with the true calibration) and truth.jsonl (one
// canonical-JSON SSL_DetectionFrame per line, frames in order, camera by
// camera within a frame). <cam> is the camera id. Throws InputError(out_dir,
// ...) when the directory cannot be written.
void writeScene(const SceneSpec& spec, const std::string& out_dir);

}  // namespace dv

#include "app/debug_views.h"

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "pipeline/cpu_pipeline.h"

namespace dv::app {

namespace {

// OpenCV names Bayer codes by the second row's colors, so an RGGB sensor is
// its "BG" pattern.
int demosaicCode(PixelFormat f) {
  switch (f) {
    case PixelFormat::BayerRggb8: return cv::COLOR_BayerBG2BGR;
    case PixelFormat::BayerGrbg8: return cv::COLOR_BayerGB2BGR;
    case PixelFormat::BayerGbrg8: return cv::COLOR_BayerGR2BGR;
    case PixelFormat::BayerBggr8: return cv::COLOR_BayerRG2BGR;
    case PixelFormat::Bgr8: break;
  }
  return -1;
}

void save(const std::string& path, const cv::Mat& image, std::vector<std::string>& written) {
  if (image.empty()) return;
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw InputError(path, "cannot write the debug image");
  written.push_back(path);
}

cv::Scalar teamColor(Team t) {
  return t == Team::Yellow ? cv::Scalar(0, 230, 255) : cv::Scalar(255, 120, 0);
}

}  // namespace

cv::Mat frameToBgr(const Frame& frame) {
  cv::Mat bgr;
  const int code = demosaicCode(frame.format);
  if (code >= 0 && frame.image.channels() == 1) {
    cv::cvtColor(frame.image, bgr, code);
  } else {
    bgr = frame.image.clone();
  }
  return bgr;
}

std::vector<std::string> writeDebugViews(const std::string& dir, uint32_t camera_id,
                                         const Frame& frame, const CameraProcessor& processor,
                                         const Detections& detections) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot create the debug directory: " + ec.message());
  const std::string prefix =
      (std::filesystem::path(dir) / ("cam" + std::to_string(camera_id) + "_frame" +
                                     std::to_string(frame.index) + "_"))
          .string();
  std::vector<std::string> written;
  const cv::Mat raw = frameToBgr(frame);
  save(prefix + "raw.png", raw, written);
  // The views come from the CPU reference run on this frame, whatever backend
  // the processor uses: only it keeps its intermediate images.
  CpuPipeline pipeline(processor.camera(), processor.field(), processor.pipeline().options());
  BlobList reference_blobs;
  pipeline.process(frame.image, reference_blobs);
  const cv::Mat rectified = pipeline.debugRectified();
  save(prefix + "rectified.png", rectified, written);
  save(prefix + "gradient.png", pipeline.debugGradient(), written);
  save(prefix + "score.png", pipeline.debugScore(), written);

  if (!rectified.empty()) {
    cv::Mat blobs = rectified.clone();
    for (const Blob& b : reference_blobs.blobs) {
      const cv::Point c(static_cast<int>(std::lround(b.grid.x)), static_cast<int>(std::lround(b.grid.y)));
      cv::circle(blobs, c, 4, cv::Scalar(b.rgb[2], b.rgb[1], b.rgb[0]), -1, cv::LINE_AA);
      cv::circle(blobs, c, 5, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    }
    save(prefix + "blobs.png", blobs, written);
  }

  cv::Mat overlay = raw.clone();
  const CameraModel& cam = processor.camera();
  const double scale = std::max(1.0, overlay.cols / 1224.0);
  const int thick = static_cast<int>(std::lround(2 * scale));
  for (const RobotDetection& r : detections.robots) {
    const cv::Point c(static_cast<int>(std::lround(r.pixel.u)), static_cast<int>(std::lround(r.pixel.v)));
    // Heading: project a point 90 mm ahead at the robot's height.
    const auto tip = cam.fieldToImage({r.position.x + 90 * std::cos(r.orientation),
                                       r.position.y + 90 * std::sin(r.orientation), r.height});
    const auto rim = cam.fieldToImage({r.position.x + 90, r.position.y, r.height});
    const double radius_px =
        rim ? std::hypot(rim->u - r.pixel.u, rim->v - r.pixel.v) : 20 * scale;
    cv::circle(overlay, c, static_cast<int>(radius_px), teamColor(r.team), thick, cv::LINE_AA);
    if (tip)
      cv::line(overlay, c, cv::Point(static_cast<int>(std::lround(tip->u)), static_cast<int>(std::lround(tip->v))),
               teamColor(r.team), thick, cv::LINE_AA);
    cv::putText(overlay, std::to_string(r.id), c + cv::Point(static_cast<int>(radius_px), 0),
                cv::FONT_HERSHEY_SIMPLEX, 0.6 * scale, cv::Scalar(255, 255, 255), thick, cv::LINE_AA);
  }
  for (const BallDetection& b : detections.balls) {
    const cv::Point c(static_cast<int>(std::lround(b.pixel.u)), static_cast<int>(std::lround(b.pixel.v)));
    cv::circle(overlay, c, static_cast<int>(12 * scale), cv::Scalar(0, 128, 255), thick, cv::LINE_AA);
  }
  save(prefix + "detections.png", overlay, written);
  return written;
}

}  // namespace dv::app

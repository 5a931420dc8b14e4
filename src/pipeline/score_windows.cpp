#include "pipeline/score_windows.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "core/error.h"
#include "pipeline/bayer_sampling.h"

namespace dv {

ScoreWindows scoreWindows(double scale, BlobScoreKind kind) {
  ScoreWindows w;
  w.gradient_scale = std::ceil(kMaxBlobRadiusMm / scale) / 3.0;
  w.quadrant_radius = std::max(2, static_cast<int>(std::lround(kMaxBlobRadiusMm / scale)));
  w.circle_radius = std::max(2.0, kMaxBlobRadiusMm / scale);
  w.inner_corner = std::clamp(static_cast<int>(std::lround(kInnerCornerMm / scale)), 0, w.quadrant_radius - 1);
  const bool circle = kind == BlobScoreKind::CircleMin;
  const int window = circle ? static_cast<int>(w.circle_radius) : w.quadrant_radius;
  w.margin = window + static_cast<int>(std::floor(w.gradient_scale)) + 2;
  w.energy_window = circle ? static_cast<int>(std::lround(w.circle_radius)) : w.quadrant_radius;
  w.color_radius = std::max(1.0, kColorRadiusMm / scale);
  w.weak_reach = kWeakReachMm / scale;
  w.view_reach = std::max(1, static_cast<int>(std::ceil(kSideBlobRadiusMm / scale)));
  return w;
}

std::vector<uint8_t> peakMask(const std::vector<uint8_t>& valid, int width, int height, const ScoreWindows& w) {
  cv::Mat seen(height, width, CV_8UC1, const_cast<uint8_t*>(valid.data()));
  cv::Mat eroded;
  const int d = 2 * w.view_reach + 1;
  cv::erode(seen, eroded, cv::getStructuringElement(cv::MORPH_ELLIPSE, {d, d}), {-1, -1}, 1, cv::BORDER_CONSTANT, 0);
  std::vector<uint8_t> mask(eroded.datastart, eroded.dataend);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (x < w.margin || y < w.margin || x >= width - w.margin || y >= height - w.margin)
        mask[static_cast<size_t>(y) * width + x] = 0;
  return mask;
}

RectifiedGrid checkedGrid(const CameraModel& camera, const FieldModel& field, const PipelineOptions& opt) {
  const auto& c = camera.calibration();
  const int w = static_cast<int>(c.image_width), h = static_cast<int>(c.image_height);
  const std::string source = "camera " + std::to_string(c.camera_id);
  if (w <= 0 || h <= 0) throw InputError(source, "calibration has no image size (pixel_image_width/height)");
  if (opt.bayer != BayerPattern::None && (w % 2 || h % 2 || w < 4 || h < 4))
    throw InputError(source, "Bayer image size " + std::to_string(w) + "x" + std::to_string(h) + " is not even");
  // Grid spacing follows the color samples' spacing. An RGB frame is spaced
  // like the same camera's Bayer mosaic under the automatic choice: nearly
  // every color camera has a Bayer sensor, so its RGB frames carry no
  // chroma finer than the mosaic's. A 2448 x 2048 RGB frame at 5 m gets the
  // 5.6 mm grid of its mosaic instead of 2.8 mm (a quarter of the cells, the
  // same recall), a grazing view keeps a grid per pixel.
  PipelineOptions resolved = opt;
  if (opt.bayer == BayerPattern::None) resolved.bayer = BayerPattern::RGGB, resolved.bayer_sampling = BayerSampling::Auto;
  if (resolved.bayer_sampling == BayerSampling::Auto)
    resolved.bayer_sampling = chooseBayerSampling(camera, field, resolved).mode;
  auto g = computeRectifiedGrid(camera, field, opt.plane_height, sampleLattice(resolved).step);
  if (!g)
    throw InputError(source, "camera sees no part of the field at plane height " +
                                 std::to_string(opt.plane_height) + " mm");
  if (g->width < 8 || g->height < 8 || static_cast<double>(g->width) * g->height > 64e6)
    throw InputError(source, "rectified grid " + std::to_string(g->width) + "x" + std::to_string(g->height) +
                                 " is unusable");
  return *g;
}

}  // namespace dv

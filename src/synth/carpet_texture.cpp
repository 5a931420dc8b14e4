#include "synth/carpet_texture.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "synth/random.h"

namespace dv {

CarpetTexture::CarpetTexture(const FieldRect& area, double texel_mm, uint64_t seed)
    : x0_(area.x_min), y0_(area.y_min), inv_texel_(1.0 / texel_mm) {
  const int cols = int(std::ceil((area.x_max - area.x_min) / texel_mm)) + 2;
  const int rows = int(std::ceil((area.y_max - area.y_min) / texel_mm)) + 2;
  raster_ = cv::Mat::zeros(rows, cols, CV_32F);
  SplitMix64 rng(mixSeed(seed, 0x436172706574ull));
  // (cell size in mm, weight): soft patches, blobs, tufts, fibre clumps.
  const double octaves[][2] = {{900, 0.45}, {250, 0.35}, {60, 0.3}, {16, 0.25}};
  cv::Mat layer;
  for (const auto& oct : octaves) {
    const double cell = std::max(oct[0], texel_mm);
    const int gc = int(std::ceil(cols * texel_mm / cell)) + 3;
    const int gr = int(std::ceil(rows * texel_mm / cell)) + 3;
    cv::Mat grid(gr, gc, CV_32F);
    for (int r = 0; r < gr; ++r)
      for (int c = 0; c < gc; ++c) grid.at<float>(r, c) = float(rng.normal());
    cv::resize(grid, layer, cv::Size(int(gc * cell / texel_mm), int(gr * cell / texel_mm)), 0, 0,
               cv::INTER_CUBIC);
    raster_ += float(oct[1]) * layer(cv::Rect(0, 0, cols, rows));
  }
  cv::Scalar mean, dev;
  cv::meanStdDev(raster_, mean, dev);
  raster_ = (raster_ - mean[0]) / std::max(1e-6, dev[0]);
}

}  // namespace dv

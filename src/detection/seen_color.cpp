#include "detection/seen_color.h"

#include <algorithm>
#include <cmath>

#include "detection/clipped_color.h"
#include "pipeline/bayer_full.h"

namespace dv {

void frameRgbAt(const FrameView& frame, double u, double v, float rgb[3]) {
  const cv::Mat& im = *frame.image;
  if (frame.bayer == BayerPattern::None || im.type() == CV_8UC3) {
    const int x = std::clamp(static_cast<int>(std::lround(u)), 0, im.cols - 1);
    const int y = std::clamp(static_cast<int>(std::lround(v)), 0, im.rows - 1);
    const cv::Vec3b p = im.at<cv::Vec3b>(y, x);
    rgb[0] = p[2], rgb[1] = p[1], rgb[2] = p[0];
    return;
  }
  const double sx = u - 0.5, sy = v - 0.5;
  const int x = static_cast<int>(std::floor(sx)), y = static_cast<int>(std::floor(sy));
  const float fx = static_cast<float>(sx - x), fy = static_cast<float>(sy - y);
  float p[4][3];
  for (int n = 0; n < 4; ++n) fullBayerRgbAt(im, frame.bayer, x + (n & 1), y + (n >> 1), p[n]);
  const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  for (int c = 0; c < 3; ++c) rgb[c] = w[0] * p[0][c] + w[1] * p[1][c] + w[2] * p[2][c] + w[3] * p[3][c];
}

namespace {

// Mean RGB over the kSeenColorSteps^2 lattice across a disc of `radius`:
// at(dx, dy, u, v) gives the image position of offset (dx, dy) (false:
// none), keep(rgb) whether a sample counts. share: the kept samples' share
// of those in the image (`of_disc`: of the whole disc).
template <class At, class Keep>
SeenColor latticeMean(const FrameView& frame, double radius, bool of_disc, At at, Keep keep) {
  SeenColor out;
  if (!frame.image || frame.image->empty() || radius < 0) return out;
  const double w = frame.image->cols, h = frame.image->rows;
  double sum[3] = {0, 0, 0};
  int in_disc = 0, in_image = 0, kept = 0;
  const double step = 2 * radius / (kSeenColorSteps - 1);
  for (int j = 0; j < kSeenColorSteps; ++j)
    for (int i = 0; i < kSeenColorSteps; ++i) {
      const double dx = -radius + i * step, dy = -radius + j * step;
      if (dx * dx + dy * dy > radius * radius) continue;
      ++in_disc;
      double u = 0, v = 0;
      if (!at(dx, dy, u, v) || u < 0 || v < 0 || u > w - 1 || v > h - 1) continue;
      ++in_image;
      float c[3];
      frameRgbAt(frame, u, v, c);
      if (!keep(c)) continue;
      for (int k = 0; k < 3; ++k) sum[k] += c[k];
      ++kept;
    }
  if (kept == 0) return out;
  for (int k = 0; k < 3; ++k) out.rgb[k] = static_cast<float>(sum[k] / kept);
  out.share = static_cast<double>(kept) / (of_disc ? in_disc : in_image);
  return out;
}

}  // namespace

SeenColor seenDiscColor(const FrameView& frame, const CameraModel& camera, const FieldPoint& center,
                        double radius) {
  return latticeMean(
      frame, radius, true,
      [&](double dx, double dy, double& u, double& v) {
        const auto px = camera.fieldToImage({center.x + dx, center.y + dy, center.z});
        if (!px) return false;
        u = px->u, v = px->v;
        return true;
      },
      [](const float*) { return true; });
}

SeenColor unclippedDiscColor(const FrameView& frame, ImagePx center, double radius_px) {
  return latticeMean(
      frame, radius_px, false,
      [&](double dx, double dy, double& u, double& v) {
        u = center.u + dx, v = center.v + dy;
        return true;
      },
      [](const float* c) { return std::max({c[0], c[1], c[2]}) < kClipLevel; });
}

}  // namespace dv

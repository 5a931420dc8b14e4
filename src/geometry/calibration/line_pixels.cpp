#include "geometry/calibration/line_pixels.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"

namespace dv {

cv::Mat toBgrImage(const cv::Mat& image, const std::string& source) {
  if (image.empty()) throw InputError(source, "empty image");
  if (image.depth() != CV_8U) throw InputError(source, "expected an 8-bit image");
  cv::Mat bgr;
  if (image.channels() == 1) {
    if (image.cols < 4 || image.rows < 4) throw InputError(source, "image too small");
    // OpenCV names Bayer patterns by the second row: RGGB is its BayerBG.
    cv::cvtColor(image, bgr, cv::COLOR_BayerBG2BGR);
  } else if (image.channels() == 3) {
    bgr = image;
  } else if (image.channels() == 4) {
    cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  } else {
    throw InputError(source, "unsupported channel count " + std::to_string(image.channels()));
  }
  return bgr;
}

cv::Mat loadCalibrationImage(const std::string& path) {
  const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (raw.empty()) throw InputError(path, "cannot read an image from this file");
  if (raw.depth() != CV_8U) throw InputError(path, "expected an 8-bit image");
  if (raw.channels() == 1) {
    toBgrImage(raw, path);  // validates the size
    return raw;
  }
  return toBgrImage(raw, path);
}

cv::Mat lineBrightness(const cv::Mat& image) {
  cv::Mat gray;
  if (image.channels() == 1) {
    const cv::Matx33f binomial(1, 2, 1, 2, 4, 2, 1, 2, 1);
    cv::filter2D(image, gray, CV_8U, cv::Mat(binomial * (1.0f / 16)), cv::Point(-1, -1), 0,
                 cv::BORDER_REFLECT_101);
  } else {
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  }
  return gray;
}

int halfLineWidthPx(double mm_per_px, double line_thickness_mm) {
  if (!(mm_per_px > 0)) return 3;
  const double width_px = line_thickness_mm / mm_per_px;
  return std::clamp(int(std::ceil(width_px / 2)) + 1, 2, 12);
}

cv::Mat detectLinePixels(const cv::Mat& image, const LinePixelOptions& o) {
  const cv::Mat gray = lineBrightness(image);
  // Colour is judged on a smoothed image: demosaicing paints thin white
  // lines with alternating colour fringes.
  cv::Mat bgr;
  cv::blur(image.channels() == 1 ? toBgrImage(image, "image") : image, bgr, cv::Size(5, 5));
  cv::Mat g16;
  gray.convertTo(g16, CV_16S);
  const int h = std::max(1, o.half_width_px);
  const int rows = gray.rows, cols = gray.cols;
  cv::Mat mask(rows, cols, CV_8UC1, cv::Scalar(0));
  const int t = o.threshold;
  // Colour spread: white lines are grey-ish, markers are saturated.
  cv::Mat spread;
  {
    std::vector<cv::Mat> ch;
    cv::split(bgr, ch);
    cv::Mat mx, mn;
    cv::max(ch[0], ch[1], mx);
    cv::max(mx, ch[2], mx);
    cv::min(ch[0], ch[1], mn);
    cv::min(mn, ch[2], mn);
    cv::subtract(mx, mn, spread);
  }
  for (int y = h; y < rows - h; ++y) {
    const int16_t* c = g16.ptr<int16_t>(y);
    const int16_t* up = g16.ptr<int16_t>(y - h);
    const int16_t* dn = g16.ptr<int16_t>(y + h);
    const uint8_t* sp = spread.ptr<uint8_t>(y);
    uint8_t* m = mask.ptr<uint8_t>(y);
    for (int x = h; x < cols - h; ++x) {
      const int v = c[x];
      const bool horizontal = v - c[x - h] > t && v - c[x + h] > t;
      const bool vertical = v - up[x] > t && v - dn[x] > t;
      if ((horizontal || vertical) && sp[x] <= o.max_colour_spread) m[x] = 255;
    }
  }
  return mask;
}

std::vector<ImagePx> maskPixels(const cv::Mat& mask, size_t max_count) {
  std::vector<cv::Point> pts;
  cv::findNonZero(mask, pts);
  std::vector<ImagePx> out;
  if (pts.empty() || max_count == 0) return out;
  const double stride = std::max(1.0, double(pts.size()) / double(max_count));
  out.reserve(std::min(pts.size(), max_count));
  for (double i = 0; i < double(pts.size()) && out.size() < max_count; i += stride) {
    const cv::Point& p = pts[size_t(i)];
    out.push_back({double(p.x), double(p.y)});
  }
  return out;
}

}  // namespace dv

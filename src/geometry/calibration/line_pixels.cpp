#include "geometry/calibration/line_pixels.h"

#include <algorithm>
#include <cmath>
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

cv::Mat calibrationImage(const cv::Mat& decoded, const std::string& source) {
  const cv::Mat bgr = toBgrImage(decoded, source);  // validates a mosaic's size too
  return decoded.channels() == 1 ? decoded : bgr;
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

namespace {

// Centre of the brightness ridge through sample c on one axis (`at(i)` reads
// sample i): the profile is climbed to its top and followed down to its foot
// on either side (at most `reach` samples each way), and the centroid taken
// of the brightness above the straight baseline between the two feet. The window so fits the line's
// width along the axis, which grows as the line turns away from it, and no
// part of a blurred line is cut off. False when nothing rises above the
// baseline.
template <typename At>
bool ridgeCentroid(At at, int c, int reach, double& centre) {
  // Up to the top first: a mask pixel may sit on the line's flank.
  const int c0 = c;
  while (c < c0 + reach && at(c + 1) > at(c)) ++c;
  while (c > c0 - reach && at(c - 1) > at(c)) --c;
  int lo = c, hi = c;
  while (lo > c - reach && at(lo - 1) <= at(lo)) --lo;
  while (hi < c + reach && at(hi + 1) <= at(hi)) ++hi;
  if (hi - lo < 2) return false;
  const double a = at(lo), b = at(hi);
  double sw = 0, swx = 0;
  for (int i = lo + 1; i < hi; ++i) {
    const double wgt = std::max(0.0, at(i) - (a + (b - a) * (i - lo) / double(hi - lo)));
    sw += wgt, swx += wgt * i;
  }
  if (!(sw > 0)) return false;
  centre = swx / sw;
  return true;
}

}  // namespace

void refineToLineCentres(const cv::Mat& gray, int half_width_px, std::vector<ImagePx>& pixels) {
  CV_Assert(gray.type() == CV_8UC1);
  const int h = std::max(1, half_width_px);
  // A line at 60 deg to the axis is twice as wide along it as across.
  const int reach = 2 * h + 1;
  // A pass reads up to 2 reach + 1 samples from where it starts, and the
  // second starts within h of the pixel.
  const int margin = h + 2 * reach + 2;
  for (auto& px : pixels) {
    const int x = int(px.u), y = int(px.v);
    if (x < margin || y < margin || x >= gray.cols - margin || y >= gray.rows - margin) continue;
    const auto at = [&](int yy, int xx) { return double(gray.at<uint8_t>(yy, xx)); };
    const auto ridge = [&](int dx, int dy) { return 2 * at(y, x) - at(y - dy * h, x - dx * h) - at(y + dy * h, x + dx * h); };
    // Along the axis on which the ridge is stronger; a second pass from the
    // first's estimate, so that a pixel on the line's flank climbs to its top.
    double c = 0;
    if (ridge(1, 0) >= ridge(0, 1)) {  // the line runs up and down: its centre along the row
      const auto row = [&](int i) { return at(y, i); };
      if (ridgeCentroid(row, x, reach, c) && std::abs(c - x) <= h &&
          ridgeCentroid(row, int(std::lround(c)), reach, c) && std::abs(c - x) <= h)
        px.u = c;
    } else {
      const auto column = [&](int i) { return at(i, x); };
      if (ridgeCentroid(column, y, reach, c) && std::abs(c - y) <= h &&
          ridgeCentroid(column, int(std::lround(c)), reach, c) && std::abs(c - y) <= h)
        px.v = c;
    }
  }
}

}  // namespace dv

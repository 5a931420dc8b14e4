#include "eval/chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace dv {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kTextScale = 0.45;
const cv::Scalar kInk(40, 40, 40), kGrid(225, 225, 225), kWhite(255, 255, 255);
// Distinct colors (BGR), in the order the series come.
const cv::Scalar kPalette[] = {{180, 119, 31}, {14, 127, 255}, {44, 160, 44}, {40, 39, 214},
                               {189, 103, 148}, {75, 86, 140}, {194, 119, 227}, {34, 189, 188}};

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return !(lo <= hi); }
  // A flat range gets some height so that it is drawn mid-chart.
  void widen() {
    if (hi - lo > 1e-12 * std::max(1.0, std::abs(hi))) return;
    const double pad = std::max(1.0, std::abs(hi) * 0.05);
    lo -= pad;
    hi += pad;
  }
};

// Round tick values (1, 2 or 5 times a power of ten) covering the range.
std::vector<double> ticks(Range& r, int wanted) {
  const double raw = (r.hi - r.lo) / std::max(1, wanted);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * magnitude;
    if (step >= raw) break;
  }
  r.lo = std::floor(r.lo / step) * step;
  r.hi = std::ceil(r.hi / step) * step;
  std::vector<double> out;
  for (double v = r.lo; v <= r.hi + step * 1e-6; v += step) out.push_back(std::abs(v) < step * 1e-9 ? 0 : v);
  return out;
}

std::string label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale = kTextScale, int align = -1) {
  int base = 0;
  const cv::Size size = cv::getTextSize(s, kFont, scale, 1, &base);
  if (align == 0) at.x -= size.width / 2;
  if (align == 1) at.x -= size.width;
  cv::putText(img, s, at, kFont, scale, kInk, 1, cv::LINE_AA);
}

// The plot area inside the image, and the mapping of values onto it.
struct Frame {
  cv::Rect area;
  Range x, y;
  cv::Point2d at(double vx, double vy) const {
    return {area.x + (vx - x.lo) / (x.hi - x.lo) * area.width,
            area.y + area.height - (vy - y.lo) / (y.hi - y.lo) * area.height};
  }
};

// Background, grid, axes, tick labels, axis labels and title.
cv::Mat drawAxes(Frame& f, const ChartStyle& style, const std::string& title, const std::string& xlabel,
                 const std::string& ylabel) {
  cv::Mat img(style.height, style.width, CV_8UC3, kWhite);
  f.area = cv::Rect(78, 40, style.width - 78 - 24, style.height - 40 - 58);
  const auto xt = ticks(f.x, 8);
  const auto yt = ticks(f.y, 6);
  for (double v : xt) {
    const int px = int(std::lround(f.at(v, f.y.lo).x));
    cv::line(img, {px, f.area.y}, {px, f.area.br().y}, kGrid, 1);
    cv::line(img, {px, f.area.br().y}, {px, f.area.br().y + 5}, kInk, 1);
    text(img, label(v), {px, f.area.br().y + 20}, kTextScale, 0);
  }
  for (double v : yt) {
    const int py = int(std::lround(f.at(f.x.lo, v).y));
    cv::line(img, {f.area.x, py}, {f.area.br().x, py}, kGrid, 1);
    cv::line(img, {f.area.x - 5, py}, {f.area.x, py}, kInk, 1);
    text(img, label(v), {f.area.x - 8, py + 5}, kTextScale, 1);
  }
  cv::rectangle(img, f.area, kInk, 1);
  text(img, title, {style.width / 2, 26}, 0.6, 0);
  text(img, xlabel, {f.area.x + f.area.width / 2, style.height - 14}, 0.5, 0);
  if (!ylabel.empty()) {  // drawn horizontally, then turned to run up the left edge
    int base = 0;
    const cv::Size size = cv::getTextSize(ylabel, kFont, 0.5, 1, &base);
    cv::Mat strip(size.height + base + 4, size.width + 4, CV_8UC3, kWhite);
    cv::putText(strip, ylabel, {2, size.height + 2}, kFont, 0.5, kInk, 1, cv::LINE_AA);
    cv::rotate(strip, strip, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int top = std::max(0, f.area.y + (f.area.height - strip.rows) / 2);
    const cv::Rect where(4, top, strip.cols, std::min(strip.rows, img.rows - top));
    strip(cv::Rect(0, 0, where.width, where.height)).copyTo(img(where));
  }
  return img;
}

bool save(const std::string& path, const cv::Mat& img, std::string* why) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, img);
  } catch (const cv::Exception& e) {
    if (why) *why = path + ": cannot write the chart (" + e.what() + ")";
    return false;
  }
  if (!ok && why) *why = path + ": cannot write the chart";
  return ok;
}

}  // namespace

bool writeLineChart(const std::string& path, const std::string& title, const std::string& xlabel,
                    const std::string& ylabel, const std::vector<Series>& series, std::string* why,
                    const ChartStyle& style) {
  Frame f;
  for (const Series& s : series) {
    for (size_t i = 0; i < std::min(s.xs.size(), s.ys.size()); ++i) {
      if (!std::isfinite(s.xs[i]) || !std::isfinite(s.ys[i])) continue;
      f.x.add(s.xs[i]);
      f.y.add(s.ys[i]);
    }
  }
  if (f.x.empty()) {
    if (why) *why = path + ": no finite values to draw";
    return false;
  }
  f.x.widen();
  f.y.widen();
  cv::Mat img = drawAxes(f, style, title, xlabel, ylabel);
  for (size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    const cv::Scalar color = kPalette[k % std::size(kPalette)];
    std::vector<cv::Point> run;
    auto flush = [&] {
      if (run.size() == 1) cv::circle(img, run[0], 2, color, cv::FILLED, cv::LINE_AA);
      if (run.size() > 1) cv::polylines(img, run, false, color, 2, cv::LINE_AA);
      run.clear();
    };
    for (size_t i = 0; i < std::min(s.xs.size(), s.ys.size()); ++i) {
      if (!std::isfinite(s.xs[i]) || !std::isfinite(s.ys[i])) {
        flush();
        continue;
      }
      const cv::Point2d p = f.at(s.xs[i], s.ys[i]);
      run.emplace_back(int(std::lround(p.x)), int(std::lround(p.y)));
    }
    flush();
  }
  // Legend: top left inside the plot on a white box, one line per series.
  int widest = 0, base = 0;
  for (const Series& s : series) widest = std::max(widest, cv::getTextSize(s.name, kFont, kTextScale, 1, &base).width);
  cv::rectangle(img, cv::Rect(f.area.x + 4, f.area.y + 4, widest + 42, 18 * int(series.size()) + 8), kWhite,
                cv::FILLED);
  for (size_t k = 0; k < series.size(); ++k) {
    const cv::Point at(f.area.x + 10, f.area.y + 18 + 18 * int(k));
    cv::line(img, at + cv::Point(0, -4), at + cv::Point(22, -4), kPalette[k % std::size(kPalette)], 3, cv::LINE_AA);
    text(img, series[k].name, at + cv::Point(28, 0));
  }
  return save(path, img, why);
}

bool writeHistogram(const std::string& path, const std::string& title, const std::string& xlabel,
                    const std::vector<double>& values, int bins, std::string* why, const ChartStyle& style) {
  Range data;
  for (double v : values) data.add(v);
  if (data.empty() || bins < 1) {
    if (why) *why = path + (bins < 1 ? ": a histogram needs at least one bin" : ": no finite values to draw");
    return false;
  }
  data.widen();
  std::vector<double> counts(size_t(bins), 0);
  const double width = (data.hi - data.lo) / bins;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    counts[size_t(std::clamp(int((v - data.lo) / width), 0, bins - 1))] += 1;
  }
  Frame f;
  f.x = data;
  f.y.add(0);
  f.y.add(*std::max_element(counts.begin(), counts.end()));
  f.y.widen();
  // The data range, not the rounded tick range, sets the bars.
  const Range bars = data;
  cv::Mat img = drawAxes(f, style, title, xlabel, "count");
  for (int b = 0; b < bins; ++b) {
    const cv::Point2d p0 = f.at(bars.lo + b * width, 0), p1 = f.at(bars.lo + (b + 1) * width, counts[size_t(b)]);
    const cv::Rect bar(cv::Point(int(std::lround(p0.x)), int(std::lround(p1.y))),
                       cv::Point(int(std::lround(p1.x)), int(std::lround(p0.y))));
    cv::rectangle(img, bar, kPalette[0], cv::FILLED);
    cv::rectangle(img, bar, kWhite, 1);
  }
  return save(path, img, why);
}

}  // namespace dv

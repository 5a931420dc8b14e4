#pragma once
// Small PNG charts drawn with OpenCV: line charts of several series against
// a common x axis, and histograms. Axes with tick labels at round values, a
// legend, a title. Used by `dotvision plot` (CSV columns) and the soak.
#include <string>
#include <vector>

namespace dv {

struct Series {
  std::string name;
  std::vector<double> xs, ys;  // same length; a NaN y breaks the line
};

struct ChartStyle {
  int width = 960;
  int height = 540;
};

// Draws every series into one chart and writes it to `path` (the extension
// picks the format, .png normally). False, with the reason in *why, when
// there is nothing finite to draw or the file cannot be written.
bool writeLineChart(const std::string& path, const std::string& title, const std::string& xlabel,
                    const std::string& ylabel, const std::vector<Series>& series, std::string* why,
                    const ChartStyle& style = {});

// A histogram of `values` (non-finite ones ignored) in `bins` equal bins
// between their smallest and largest value.
bool writeHistogram(const std::string& path, const std::string& title, const std::string& xlabel,
                    const std::vector<double>& values, int bins, std::string* why,
                    const ChartStyle& style = {});

}  // namespace dv

#include "eval/eval_plots.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "eval/chart.h"
#include "geometry/field_model.h"

namespace dv {
namespace {

constexpr int kBins = 30;
constexpr int kMapWidth = 1200;
constexpr double kMapMarginMm = 400;

// The field the misses lie on: Division B unless a point lies beyond it.
FieldModel fieldFor(const std::vector<Miss>& misses) {
  FieldModel b = FieldModel::divisionB();
  const FieldRect r = b.withBoundary();
  for (const Miss& m : misses)
    if (m.x < r.x_min || m.x > r.x_max || m.y < r.y_min || m.y > r.y_max) return FieldModel::divisionA();
  return b;
}

void writeFieldMap(const std::string& path, const std::vector<Miss>& misses) {
  const FieldModel field = fieldFor(misses);
  const FieldRect r = field.withBoundary();
  const double x0 = r.x_min - kMapMarginMm, y1 = r.y_max + kMapMarginMm;
  const double scale = kMapWidth / (r.x_max - r.x_min + 2 * kMapMarginMm);  // px per mm
  const int height = static_cast<int>((r.y_max - r.y_min + 2 * kMapMarginMm) * scale) + 60;
  cv::Mat img(height, kMapWidth, CV_8UC3, cv::Scalar(40, 110, 50));
  auto px = [&](double x, double y) {
    return cv::Point(static_cast<int>((x - x0) * scale), static_cast<int>((y1 - y) * scale));
  };
  for (const FieldLine& l : field.lines) cv::line(img, px(l.p1.x, l.p1.y), px(l.p2.x, l.p2.y), {235, 235, 235}, 2);
  for (const FieldArc& a : field.arcs) {
    const double span = a.span();
    for (int i = 0; i < 64; ++i) {
      const double t0 = a.a1 + span * i / 64, t1 = a.a1 + span * (i + 1) / 64;
      cv::line(img, px(a.center.x + a.radius * std::cos(t0), a.center.y + a.radius * std::sin(t0)),
               px(a.center.x + a.radius * std::cos(t1), a.center.y + a.radius * std::sin(t1)), {235, 235, 235}, 2);
    }
  }
  // BGR: robots missed red, wrong id yellow, false robots magenta, balls
  // missed orange discs, false balls cyan.
  struct Style {
    cv::Scalar color;
    const char* label;
  };
  const Style styles[] = {{{40, 40, 230}, "robot missed"},
                          {{0, 220, 255}, "robot wrong id"},
                          {{230, 60, 230}, "false robot"},
                          {{0, 140, 255}, "ball missed"},
                          {{230, 230, 0}, "false ball"}};
  long counts[5] = {0, 0, 0, 0, 0};
  for (const Miss& m : misses) {
    const Style& s = styles[m.kind];
    ++counts[m.kind];
    const bool ball = m.kind == Miss::BallMissed || m.kind == Miss::FalseBall;
    const int radius = std::max(3, static_cast<int>((ball ? 60 : 90) * scale));
    if (ball) {
      cv::circle(img, px(m.x, m.y), radius, s.color, cv::FILLED, cv::LINE_AA);
    } else {
      cv::circle(img, px(m.x, m.y), radius, s.color, 2, cv::LINE_AA);
    }
  }
  int x = 10;
  for (int k = 0; k < 5; ++k) {
    const std::string text = std::string(styles[k].label) + " " + std::to_string(counts[k]);
    cv::circle(img, {x + 8, height - 25}, 7, styles[k].color, cv::FILLED);
    cv::putText(img, text, {x + 20, height - 19}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {255, 255, 255}, 1, cv::LINE_AA);
    x += 230;
  }
  bool ok = false;
  try {
    ok = cv::imwrite(path, img);
  } catch (const cv::Exception&) {
  }
  if (!ok) throw InputError(path, "cannot be written");
}

}  // namespace

std::vector<std::string> writeEvalPlots(const std::string& dir, const Metrics& m) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot be created: " + ec.message());
  std::vector<std::string> written;
  auto histogram = [&](const char* name, const char* title, const char* xlabel, const std::vector<double>& v) {
    if (v.empty()) return;
    const std::string path = (std::filesystem::path(dir) / name).string();
    std::string why;
    if (!writeHistogram(path, title, xlabel, v, kBins, &why)) throw InputError(path, why);
    written.push_back(path);
  };
  histogram("robot_position_error.png", "Robot position error", "mm", m.robot_position_errors_mm);
  std::vector<double> deg;
  for (double a : m.robot_orientation_errors_rad) deg.push_back(a * 180 / kPi);
  histogram("robot_orientation_error.png", "Robot orientation error", "degrees", deg);
  histogram("ball_position_error.png", "Ball position error", "mm", m.ball_position_errors_mm);
  const std::string map = (std::filesystem::path(dir) / "field_map.png").string();
  writeFieldMap(map, m.misses);
  written.push_back(map);
  return written;
}

}  // namespace dv

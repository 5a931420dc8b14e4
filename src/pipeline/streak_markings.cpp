#include "pipeline/streak_markings.h"

#include <algorithm>

#include "pipeline/streak_windows.h"

namespace dv {

MarkingMask::MarkingMask(const CameraModel& camera, const FieldModel& field, const RectifiedGrid& grid,
                         double plane_height)
    : width_(grid.width), height_(grid.height), cells_(static_cast<size_t>(grid.width) * grid.height, 0) {
  const double step = grid.scale / 2;  // mm along a marking
  auto mark = [&](double x, double y, double thickness) {
    const double reach = (thickness / 2 + kStreakCellMm) / grid.scale;  // grid cells
    const int r = static_cast<int>(std::ceil(reach));
    const auto px = camera.fieldToImage({x, y, 0});
    if (!px) return;
    const auto on_plane = camera.imageToField(*px, plane_height);
    if (!on_plane) return;
    const GridPx g = grid.toGrid({on_plane->x, on_plane->y});
    const int cx = static_cast<int>(std::lround(g.x)), cy = static_cast<int>(std::lround(g.y));
    for (int y = std::max(0, cy - r); y <= std::min(height_ - 1, cy + r); ++y)
      for (int x = std::max(0, cx - r); x <= std::min(width_ - 1, cx + r); ++x)
        if (std::hypot(x - g.x, y - g.y) <= reach) cells_[static_cast<size_t>(y) * width_ + x] = 1;
  };
  for (const FieldLine& l : field.lines) {
    const double len = std::hypot(l.p2.x - l.p1.x, l.p2.y - l.p1.y);
    const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
    for (int i = 0; i <= n; ++i) mark(l.p1.x + (l.p2.x - l.p1.x) * i / n, l.p1.y + (l.p2.y - l.p1.y) * i / n, l.thickness);
  }
  for (const FieldArc& a : field.arcs) {
    const int n = std::max(1, static_cast<int>(std::ceil(a.span() * a.radius / step)));
    for (int i = 0; i <= n; ++i) {
      const double t = a.a1 + a.span() * i / n;
      mark(a.center.x + a.radius * std::cos(t), a.center.y + a.radius * std::sin(t), a.thickness);
    }
  }
}

}  // namespace dv

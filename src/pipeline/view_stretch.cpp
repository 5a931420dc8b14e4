#include "pipeline/view_stretch.h"

#include <algorithm>
#include <cmath>

#include "pipeline/whitening_form.h"

namespace dv {

double viewStretch(const CameraModel& camera, const FieldMm& p, double plane_height, double dir[2]) {
  dir[0] = 0, dir[1] = 0;
  const Eigen::Vector3d& c = camera.position();
  const double dx = p.x - c.x(), dy = p.y - c.y(), dh = std::hypot(dx, dy);
  if (dh < 1) return 1;
  const double ux = dx / dh, uy = dy / dh;
  // Field size of an image pixel along and across the ray, from the model
  // itself (distortion included): image distance of a small step each way.
  constexpr double kStep = 5;  // mm
  const auto p0 = camera.fieldToImage({p.x, p.y, plane_height});
  const auto pa = camera.fieldToImage({p.x + kStep * ux, p.y + kStep * uy, plane_height});
  const auto pc = camera.fieldToImage({p.x - kStep * uy, p.y + kStep * ux, plane_height});
  if (!p0 || !pa || !pc) return 1;
  const double ia = std::hypot(pa->u - p0->u, pa->v - p0->v), ic = std::hypot(pc->u - p0->u, pc->v - p0->v);
  if (!(ia > 0) || !(ic > 0)) return 1;
  const double along = kChromaBlurPx * kStep / ia, across = kChromaBlurPx * kStep / ic;
  const double r = kStretchBlobRadiusMm;
  dir[0] = ux, dir[1] = -uy;  // grid rows run toward -y
  return std::hypot(r, along) / std::hypot(r, across);
}

GradientForms gradientForms(const CameraModel& camera, const RectifiedGrid& grid, double plane_height) {
  GradientForms f;
  f.blocks_x = (grid.width + kFormBlock - 1) / kFormBlock;
  f.blocks_y = (grid.height + kFormBlock - 1) / kFormBlock;
  const size_t n = static_cast<size_t>(f.blocks_x) * f.blocks_y;
  f.coef.assign(6 * n, 0.f);
  f.plain.assign(n, 1);
  f.plain_row.assign(f.blocks_y, 1);
  for (int by = 0; by < f.blocks_y; ++by) {
    for (int bx = 0; bx < f.blocks_x; ++bx) {
      const double cx = std::min(grid.width - 1.0, (bx + 0.5) * kFormBlock - 0.5);
      const double cy = std::min(grid.height - 1.0, (by + 0.5) * kFormBlock - 0.5);
      double d[2];
      const double s = viewStretch(camera, grid.toField({cx, cy}), plane_height, d);
      const double k = std::round((s - 1) / kStretchStep) * kStretchStep;
      float* c = &f.coef[6 * (static_cast<size_t>(by) * f.blocks_x + bx)];
      if (!(1 + k >= kMinStretch)) {
        c[0] = 0, c[1] = 1, c[2] = 0, c[3] = 1, c[4] = 0, c[5] = 1;
        continue;
      }
      whiteningForm(k, d[0], d[1], c);
      f.plain[static_cast<size_t>(by) * f.blocks_x + bx] = 0;
      f.plain_row[by] = 0;
      f.any = true;
    }
  }
  return f;
}

}  // namespace dv

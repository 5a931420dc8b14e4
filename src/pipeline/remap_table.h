#pragma once
// Rectification (thesis §5.2.4): for every grid cell, where its field point
// on the plane lies in the co-sited RGBX image, as a top-left sample index and
// bilinear fractions. Computed once per camera geometry.
#include <cstdint>
#include <vector>

#include "geometry/camera_model.h"
#include "pipeline/rectified_grid.h"

namespace dv {

// Where the color samples the table reads lie: sample (i, j) is centered on
// full pixel (step * i + offset, step * j + offset).
struct SampleLattice {
  int step = 2;
  double offset = 0.5;
};

struct RemapTable {
  int width = 0, height = 0;      // grid size
  int src_width = 0, src_height = 0;  // RGBX image size
  std::vector<int32_t> index;     // top-left sample: y0 * src_width + x0
  std::vector<uint16_t> frac;     // fx | fy << 8, in 1/256 of a sample
  std::vector<uint8_t> valid;     // 1 where the cell's point is seen by the camera
  // The RGBX samples the table reads: columns [x_begin, x_end), rows
  // [y_begin, y_end). Only these need to be produced per frame.
  int x_begin = 0, x_end = 0, y_begin = 0, y_end = 0;

  // lattice: {2, 0.5} for Bayer subsampling, {1, 0.5} for full Bayer
  // sampling (2x2 windows at every pixel), {1, 0} for RGB (sampleLattice()).
  template <class Pool>
  void build(const CameraModel& camera, const RectifiedGrid& grid, double plane_height,
             SampleLattice lattice, Pool& pool);

  // True when grid rows run mostly along image columns (a camera turned by
  // about 90 degrees): then each cell of a grid row reads another image row.
  bool runsAlongColumns() const;
  // The same table for the transposed sample image (sample (x, y) stored at
  // x * stride + y, stride >= src_height): index and fractions with x and y
  // exchanged, src_width = stride. Bilinear interpolation through it visits
  // the same four samples with the same weights.
  RemapTable transposed(int stride) const;
};

}  // namespace dv

#include <algorithm>
#include <cmath>

namespace dv {

template <class Pool>
void RemapTable::build(const CameraModel& camera, const RectifiedGrid& grid, double plane_height,
                       SampleLattice lattice, Pool& pool) {
  const int sample_step = lattice.step;
  const double offset = lattice.offset;
  width = grid.width;
  height = grid.height;
  const auto& c = camera.calibration();
  src_width = static_cast<int>(c.image_width) / sample_step;
  src_height = static_cast<int>(c.image_height) / sample_step;
  const size_t n = static_cast<size_t>(width) * height;
  index.assign(n, 0);
  frac.assign(n, 0);
  valid.assign(n, 0);
  pool.parallelFor(height, [&](int y_begin, int y_end) {
    for (int y = y_begin; y < y_end; ++y) {
      for (int x = 0; x < width; ++x) {
        const FieldMm f = grid.toField({static_cast<double>(x), static_cast<double>(y)});
        const auto px = camera.fieldToImage({f.x, f.y, plane_height});
        const size_t k = static_cast<size_t>(y) * width + x;
        if (!px || !std::isfinite(px->u) || !std::isfinite(px->v)) continue;
        double sx = (px->u - offset) / sample_step;
        double sy = (px->v - offset) / sample_step;
        valid[k] = sx >= 0 && sy >= 0 && sx <= src_width - 1 && sy <= src_height - 1;
        // Outside the image: repeat the border sample (zero gradient there).
        sx = std::clamp(sx, 0.0, src_width - 1.0);
        sy = std::clamp(sy, 0.0, src_height - 1.0);
        // Round to 1/256 sample first, then split into sample and fraction.
        const long qx = std::lround(sx * 256), qy = std::lround(sy * 256);
        int x0 = static_cast<int>(qx >> 8), fx = static_cast<int>(qx & 255);
        int y0 = static_cast<int>(qy >> 8), fy = static_cast<int>(qy & 255);
        if (x0 > src_width - 2) x0 = src_width - 2, fx = 255;
        if (y0 > src_height - 2) y0 = src_height - 2, fy = 255;
        index[k] = y0 * src_width + x0;
        frac[k] = static_cast<uint16_t>(fx | (fy << 8));
      }
    }
  });
  // Cells that were skipped (no image point) keep index 0, which is read.
  x_begin = src_width, x_end = 0, y_begin = src_height, y_end = 0;
  for (size_t k = 0; k < n; ++k) {
    const int x0 = index[k] % src_width, y0 = index[k] / src_width;
    x_begin = std::min(x_begin, x0), x_end = std::max(x_end, x0 + 2);
    y_begin = std::min(y_begin, y0), y_end = std::max(y_end, y0 + 2);
  }
}

inline bool RemapTable::runsAlongColumns() const {
  long along_x = 0, along_y = 0;
  for (int y = 0; y < height; y += 8) {
    for (int x = 0; x + 1 < width; ++x) {
      const size_t k = static_cast<size_t>(y) * width + x;
      if (!valid[k] || !valid[k + 1]) continue;
      along_x += std::abs(index[k + 1] % src_width - index[k] % src_width);
      along_y += std::abs(index[k + 1] / src_width - index[k] / src_width);
    }
  }
  return along_y > along_x;
}

inline RemapTable RemapTable::transposed(int stride) const {
  RemapTable t = *this;
  t.src_width = stride;
  t.src_height = src_width;
  std::swap(t.x_begin, t.y_begin);
  std::swap(t.x_end, t.y_end);
  for (size_t k = 0; k < index.size(); ++k) {
    const int x0 = index[k] % src_width, y0 = index[k] / src_width;
    t.index[k] = x0 * stride + y0;
    t.frac[k] = static_cast<uint16_t>((frac[k] >> 8) | ((frac[k] & 255) << 8));
  }
  return t;
}

}  // namespace dv

#pragma once
// Blobs seen at a grazing angle are stretched on the rectified grid along the
// viewing direction: an image pixel covers 1 / sin(elevation) times more
// field along the ray from the camera's foot point than across it, so the
// chroma blur of a few pixels smears a 40 mm side blob into an ellipse (at
// 5-7 m from a camera 1.6 m high, 1.5-2 times longer than wide, its long axis
// pointing at the camera, i.e. at any angle on the grid). The gradient dot
// product gx * gy of such an ellipse is negative over most of its rim and the
// minimum quadrant score fails.
//
// Where the stretch is known from the camera model, the gradient is
// whitened before the product: g' = W g with W = I + (s - 1) d d^T, d the
// viewing direction on the grid and s the stretch, so an ellipse's gradient
// field looks like a round blob's; the gradient energy of the ratio test
// uses the same W (|W g|^2). G = g'x * g'y is a quadratic form
// a gx^2 + b gx gy + c gy^2 per chroma channel, with (a, b, c) per block of
// cells (the stretch varies slowly). Where s rounds below kMinStretch
// (every top-down camera) a block is plain and the plain product is used,
// bit for bit.
// The quadrant score only (the circle score option and the inspection view
// of G keep the plain product).
//
// Measured on the side_view preset (6 placements, 60 robots, the robots
// 4.8..7.1 m away): 8 of the 10 far robots lost with the plain product are
// found, precision stays 1.000.
#include <cstdint>
#include <vector>

#include "geometry/camera_model.h"
#include "pipeline/rectified_grid.h"

namespace dv {

// Chroma blur assumed in image pixels: the period of a Bayer mosaic's red
// and blue sites (2 px), below which no chroma detail is sampled.
inline constexpr double kChromaBlurPx = 2;
// Blob radius the stretch is measured for (a side blob, the smallest).
inline constexpr double kStretchBlobRadiusMm = 20;
// Stretches are rounded to this step.
inline constexpr double kStretchStep = 0.125;
// Rounded stretches below this leave a block plain. A blob stretched a
// quarter still scores with the plain product (at 1224 x 1024 the tilted
// views' far blobs were measured so); whitening there found a few more
// robots, but mostly ones whose fourth side blob stays below the threshold
// and whose id is then a guess (the outsider scene of scene_cli_test: 3
// more robots, one of them reported with a wrong id in both frames, id
// accuracy 1.000 -> 0.949; the scene sweep's 25° tilt at 1224 x 1024:
// recall 0.909 -> 0.977). The side view's far blobs stretch 1.5..2.
inline constexpr double kMinStretch = 1.375;
// Cells per block side of the form table.
inline constexpr int kFormBlock = 16;

struct GradientForms {
  int blocks_x = 0, blocks_y = 0;
  // Per block, 6 floats: the product form (a, b, c) and the energy form
  // (qxx, qxy, qyy): energy = 1/2 sum_c qxx gx^2 + 2 qxy gx gy + qyy gy^2.
  std::vector<float> coef;
  std::vector<uint8_t> plain_row;  // per block row: 1 when all its blocks are plain
  std::vector<uint8_t> plain;      // per block
  bool any = false;                // some block is not plain

  const float* block(int x, int y) const {
    return coef.data() + 6 * (static_cast<size_t>(y / kFormBlock) * blocks_x + x / kFormBlock);
  }
  bool plainAt(int x, int y) const {
    return !any || plain[static_cast<size_t>(y / kFormBlock) * blocks_x + x / kFormBlock];
  }
  bool plainRow(int y) const { return !any || plain_row[y / kFormBlock]; }
  // The forms of block row y / kFormBlock (6 floats per block).
  const float* row(int y) const { return coef.data() + 6 * static_cast<size_t>(y / kFormBlock) * blocks_x; }
};

// Stretch of a blob of kStretchBlobRadiusMm at field point p on the plane:
// hypot(R, blur along) / hypot(R, blur across) with the blur kChromaBlurPx
// times the field size of an image pixel along and across the ray; 1 where
// the camera looks straight down. `dir` gets the viewing direction on the
// grid (x right, y down).
double viewStretch(const CameraModel& camera, const FieldMm& p, double plane_height, double dir[2]);

GradientForms gradientForms(const CameraModel& camera, const RectifiedGrid& grid, double plane_height);

}  // namespace dv

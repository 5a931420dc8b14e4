#pragma once
// The rectified field grid of one camera: which field rectangle it covers and
// at what scale. Rows run toward -y so that an image of the grid shows the
// field as seen from above with +x right and +y up.
#include <optional>

#include "core/units.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"

namespace dv {

struct RectifiedGrid {
  double x0 = 0, y0 = 0;  // field mm of the center of cell (0, 0)
  double scale = 1;       // mm per cell
  int width = 0, height = 0;

  FieldMm toField(GridPx g) const { return {x0 + g.x * scale, y0 - g.y * scale}; }
  GridPx toGrid(FieldMm f) const { return {(f.x - x0) / scale, (y0 - f.y) / scale}; }
};

// A camera whose samples lie further apart on the field than
// kResampleAboveMm gets a grid of kLowResolutionGridMm instead (see
// computeRectifiedGrid).
inline constexpr double kResampleAboveMm = 6.8;
inline constexpr double kLowResolutionGridMm = 5.6;

// Grid of the part of the field plus boundary that the camera sees on the
// plane z = plane_height (axis-parallel box), at the mean field distance
// between neighbouring samples of the image the grid is resampled from
// (`sample_step` full pixels apart: 2 for Bayer subsampling, 1 for RGB),
// except for low-resolution cameras (see kResampleAboveMm).
// Empty when the camera sees nothing of it.
std::optional<RectifiedGrid> computeRectifiedGrid(const CameraModel& camera,
                                                  const FieldModel& field, double plane_height,
                                                  int sample_step);

}  // namespace dv

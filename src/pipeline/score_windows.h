#pragma once
// What the CPU reference and the OpenCL backend must agree on before any
// pixel is touched: the blob constants in millimetres and the window sizes
// they become on a camera's grid. One definition, so tuning cannot drift
// between the backends.
#include <cstdint>
#include <vector>

#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "pipeline/pipeline_options.h"
#include "pipeline/rectified_grid.h"

namespace dv {

// Largest blob radius (center blob, thesis §5.2.7.3).
inline constexpr double kMaxBlobRadiusMm = 25;
// Smallest pattern blob radius (a side blob): a peak counts where a blob of
// this size would be seen whole (peakMask).
inline constexpr double kSideBlobRadiusMm = 20;
// Radius over which a blob's color is averaged: the side blob radius minus a
// margin for blur and position error.
inline constexpr double kColorRadiusMm = 13;
// Smallest (max - min) / max of a blob's mean color: pattern colors and the
// ball are 0.6..0.9, white lines with carpet around them 0.1..0.2.
inline constexpr float kMinBlobSaturation = 0.25f;
// Peaks closer than this belong to the same blob.
inline constexpr double kMinBlobDistanceMm = 20;
// Weak peaks (BlobList::weak) are looked for only this close to a blob: a
// side blob lies 65 mm from its robot's center blob, and the detector
// searches side blobs up to 90 mm from a center (DetectorOptions).
inline constexpr double kWeakReachMm = 90;
// Inner corner of each quadrant left out of the score: crossings of 10 mm
// lines make the same checkerboard as a blob, but only near the center.
inline constexpr double kInnerCornerMm = 10;
// The reported score is the weakest quadrant's mean gradient dot product
// divided by (mean gradient energy in the window + this floor). The ratio is
// a shape measure: high for round blobs, low for lines, crossings and
// corners, whose edges carry energy but little diagonal product. The floor
// (in the brightness-normalised chroma units, so independent of exposure)
// keeps faint texture from reaching high ratios.
inline constexpr float kEnergyFloor = 0.01f;

// Window sizes in grid cells for a grid of `scale` mm per cell.
struct ScoreWindows {
  double gradient_scale = 1;  // 1/3 * ceil(25 mm / scale) (thesis §5.2.7.4)
  int quadrant_radius = 2;
  double circle_radius = 2;
  int inner_corner = 0;       // left out of each quadrant
  int margin = 1;             // cells at the edge without a full score window
  int view_reach = 1;         // cells around a peak that must be seen (peakMask)
  int energy_window = 2;      // half size of the gradient energy window
  double color_radius = 1;
  double weak_reach = 1;      // kWeakReachMm in cells
};
ScoreWindows scoreWindows(double scale, BlobScoreKind kind);

// Where a peak may count: grid cells whose disc of w.view_reach cells lies
// in the camera's view (`valid`, grid sized, 1 = seen) and whose whole score
// window lies in the grid. A side blob there is seen whole; the rest of its
// window may read the repeated border samples (remap_table.h), whose
// gradient across the image border is zero. Requiring the whole window
// (w.margin, ~40 mm at 3.65 mm cells) to be seen lost the side view's
// robots whose side blobs lay in the image within that of its border.
std::vector<uint8_t> peakMask(const std::vector<uint8_t>& valid, int width, int height, const ScoreWindows& w);

// The grid of a camera for these options, with the checks both backends
// make: an image size in the calibration, an even size for Bayer input, a
// view of the field, a usable grid. Throws InputError naming the camera.
RectifiedGrid checkedGrid(const CameraModel& camera, const FieldModel& field, const PipelineOptions& opt);

}  // namespace dv

#pragma once
// CPU reference pixel pipeline (thesis §5.2.3-5.2.9, A.3): raw camera frame ->
// blobs on the rectified field grid of one camera.
//
//   Bayer 2x2 subsampling (channels co-sited at the cell center), or the
//   same at every pixel for cameras whose 2x2 cells are coarse on the field
//   (bayer_sampling.h)
//   -> rectification to the plane z = plane_height through a remap table
//   -> chroma (dRGB or YUV), divided by local brightness so scores do not
//      depend on exposure or uneven light
//   -> color gradient dot product at scale 1/3 * ceil(25 mm / field scale)
//   -> minimum quadrant sum through a summed-area table (or exact circle)
//   -> 4-way local peaks above the threshold, quadratic peak interpolation,
//      mean blob color.
// Where the grid is fine, the stages up to the peaks run first over a grid of
// twice the spacing (under 2x2 subsampling on the mosaic binned to half
// size), and the full grid is scored only around the peaks found there
// (PipelineOptions::coarse_search).
// Tables and buffers are built once per camera; process() does not allocate
// after the first frame.
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "core/units.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "pipeline/blob.h"
#include "pipeline/pipeline_options.h"
#include "pipeline/rectified_grid.h"

namespace dv {

class CpuPipeline {
 public:
  // Builds the remap table and all buffers. Throws InputError when the camera
  // sees no part of the field (plus boundary) or the calibration has no image
  // size.
  CpuPipeline(const CameraModel& camera, const FieldModel& field, const PipelineOptions& opt);
  ~CpuPipeline();
  CpuPipeline(CpuPipeline&&) noexcept;
  CpuPipeline& operator=(CpuPipeline&&) noexcept;

  // raw: CV_8UC1 Bayer of the calibration's image size (opt.bayer != None), or
  // CV_8UC3 BGR (always accepted). Returns false, leaves `out` empty and sets
  // lastError() on a frame of the wrong size or type.
  bool process(const cv::Mat& raw, BlobList& out);
  // Places where weak peaks also count from the next frame on (blob.h).
  void expect(const ExpectedPlaces& places);
  const std::string& lastError() const;

  const RectifiedGrid& grid() const;
  const StageTimes& times() const;
  // Options as used: bayer_sampling resolved (never Auto).
  const PipelineOptions& options() const;
  // How the camera's mosaic is sampled and why (one line for the log).
  const std::string& samplingNote() const;
  // Gradient distance (cells) and quadrant radius (cells) in use.
  double gradientScale() const;
  int quadrantRadius() const;

  // Full-resolution camera pixel of a grid position (for pixel_x/pixel_y).
  // Empty where the grid cell has no image position (beyond the horizon).
  std::optional<ImagePx> gridToImage(GridPx g) const;

  // Inspection views of the last frame, 8-bit, grid sized (not for hot paths):
  // rectified color (BGR), gradient dot product and blob score (gray, 128 = 0).
  cv::Mat debugRectified() const;
  cv::Mat debugGradient() const;
  cv::Mat debugScore() const;
  // Raw blob score plane of the last frame (grid sized, row-major).
  const float* scoreData() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dv

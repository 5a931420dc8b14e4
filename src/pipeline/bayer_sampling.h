#pragma once
// Which Bayer sampling a camera gets (PipelineOptions::bayer_sampling).
//
// Subsampling each 2x2 cell into one sample (thesis §5.2.3) keeps a quarter
// of the samples, which is enough where a cell covers little field: 5.5 mm
// for the 2448 x 2048 camera 5 m above the field. The blob score compares
// colors a gradient distance apart (a third of the largest blob radius,
// 8.3 mm; score_windows.h). Where a cell covers more field than that, the
// gradient across a blob rim is an interpolation between the same two
// samples and side blobs lose their shape: a 1224 x 1024 camera at that
// height (11 mm per cell), or the far part of a tilted camera's view, where
// cells are stretched along the viewing direction. Such cameras get full
// sampling: a co-sited sample per pixel (bayer_full.h), four times the
// samples for the first stage, and the grid follows the finer samples.
// Measured (CPU, 2 threads, loaded machine): 1224 x 1024 top-down 13 -> 18 ms
// per frame, robot recall 0.977 -> 1.0; the side view 17 -> 50 ms (its grid
// goes from 5.6 to 3.65 mm) for no change in recall (its far robots are
// limited by the optics, not by the sampling).
#include <string>

#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "pipeline/pipeline_options.h"
#include "pipeline/remap_table.h"
#include "pipeline/score_windows.h"

namespace dv {

// Longest field extent of a 2x2 cell that subsampling serves: the gradient
// distance of the blob score.
inline constexpr double kMaxCellFootprintMm = kMaxBlobRadiusMm / 3;
// Full sampling once cells are coarser than that over more than this part of
// the visible field area. A camera looking straight down has the same
// footprint everywhere (up to lens distortion), so this only decides for
// tilted cameras: any part where robots would be missed counts, a sliver at
// the edge of the view does not.
inline constexpr double kMaxCoarseAreaFraction = 0.05;

struct BayerSamplingChoice {
  BayerSampling mode = BayerSampling::Subsample;  // never Auto
  bool automatic = false;       // chosen by the rule, not requested
  double coarse_fraction = 0;   // visible field area with cells > kMaxCellFootprintMm
  double median_cell_mm = 0;    // median longer extent of a 2x2 cell over that area
  bool rgb = false;             // RGB input: a sample per pixel, nothing to choose
  // One line for the log, e.g. "Bayer sampling full (auto: 2x2 cells cover
  // 11.1 mm of field (median), coarser than 8.3 mm over 100% of the view)".
  std::string describe() const;
};

// Resolves opt.bayer_sampling for this camera (Auto by the rule above).
BayerSamplingChoice chooseBayerSampling(const CameraModel& camera, const FieldModel& field,
                                        const PipelineOptions& opt);

// Where the pipeline's color samples lie for resolved options: Bayer
// subsampling {2, 0.5}, full Bayer sampling {1, 0.5} (the center of the 2x2
// window at the pixel), RGB {1, 0}.
SampleLattice sampleLattice(const PipelineOptions& opt);

}  // namespace dv

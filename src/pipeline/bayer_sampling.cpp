#include "pipeline/bayer_sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace dv {

std::string BayerSamplingChoice::describe() const {
  if (rgb) return "RGB input (a sample per pixel)";
  char buf[256];
  if (median_cell_mm > 0) {
    std::snprintf(buf, sizeof buf,
                  "Bayer sampling %s (%s: 2x2 cells cover %.1f mm of field (median), coarser than "
                  "%.1f mm over %.0f%% of the view)",
                  bayerSamplingName(mode), automatic ? "auto" : "requested", median_cell_mm,
                  kMaxCellFootprintMm, 100 * coarse_fraction);
  } else {
    std::snprintf(buf, sizeof buf, "Bayer sampling %s (%s)", bayerSamplingName(mode),
                  automatic ? "auto" : "requested");
  }
  return buf;
}

BayerSamplingChoice chooseBayerSampling(const CameraModel& camera, const FieldModel& field,
                                        const PipelineOptions& opt) {
  BayerSamplingChoice choice;
  if (opt.bayer == BayerPattern::None) {
    choice.rgb = true;
    choice.mode = BayerSampling::Full;
    return choice;
  }
  // Field-area weighted: robots are spread over the field, not the image.
  const auto& c = camera.calibration();
  const double w = c.image_width, h = c.image_height;
  const FieldRect area = field.withBoundary();
  const double step = 50;  // mm
  std::vector<float> cells;
  long coarse = 0;
  for (double y = area.y_min + step / 2; y < area.y_max; y += step) {
    for (double x = area.x_min + step / 2; x < area.x_max; x += step) {
      const auto px = camera.fieldToImage({x, y, opt.plane_height});
      if (!px || !(px->u >= 0 && px->v >= 0 && px->u <= w - 1 && px->v <= h - 1)) continue;
      const auto pu = camera.imageToField({px->u + 2, px->v}, opt.plane_height);
      const auto pv = camera.imageToField({px->u, px->v + 2}, opt.plane_height);
      // A neighbour beyond the horizon: as coarse as it gets.
      double extent = 1e9;
      if (pu && pv)
        extent = std::max(std::hypot(pu->x - x, pu->y - y), std::hypot(pv->x - x, pv->y - y));
      cells.push_back(static_cast<float>(extent));
      coarse += extent > kMaxCellFootprintMm;
    }
  }
  if (!cells.empty()) {
    auto mid = cells.begin() + static_cast<long>(cells.size() / 2);
    std::nth_element(cells.begin(), mid, cells.end());
    choice.median_cell_mm = *mid;
    choice.coarse_fraction = static_cast<double>(coarse) / static_cast<double>(cells.size());
  }
  if (opt.bayer_sampling == BayerSampling::Auto) {
    choice.automatic = true;
    choice.mode = choice.coarse_fraction > kMaxCoarseAreaFraction ? BayerSampling::Full
                                                                  : BayerSampling::Subsample;
  } else {
    choice.mode = opt.bayer_sampling;
  }
  return choice;
}

SampleLattice sampleLattice(const PipelineOptions& opt) {
  if (opt.bayer == BayerPattern::None) return {1, 0.0};
  return {opt.bayer_sampling == BayerSampling::Full ? 1 : 2, 0.5};
}

}  // namespace dv

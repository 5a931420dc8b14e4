#pragma once
// Blob selection (thesis §5.2.8, §5.2.9): 4-way local peaks of the blob score
// above a threshold, refined by quadratic peak interpolation.
#include <cstdint>
#include <utility>
#include <vector>

#include "core/units.h"
#include "pipeline/blob_spacing.h"

namespace dv {

struct PeakCandidate {
  int x = 0, y = 0;
  float score = 0;
};

// Scans rows [y_begin, y_end) (cells within `margin` of the border are
// skipped) and appends peaks where mask != 0 to out[count..capacity).
// Returns the new count; stops silently when full.
int findPeakRows(const float* score, const uint8_t* mask, int width, int height, int margin,
                 float threshold, PeakCandidate* out, int count, int capacity, int y_begin,
                 int y_end);

// Weak peaks (hysteresis, as in Canny's edges): the same peak test as
// findPeakRows, but only at cells of rows [y_begin, y_end) closer than
// reach.distance() to a blob kept in `reach`, so the cost follows the
// blobs rather than the carpet. `near` holds the same n positions sorted by
// y; `spans` is scratch space (reused, so it stops growing).
int findPeaksNear(const float* score, const uint8_t* mask, int width, int height, int margin,
                  float threshold, const GridPx* near, int n, const BlobSpacing& reach,
                  std::vector<std::pair<int, int>>& spans, PeakCandidate* out, int count, int capacity,
                  int y_begin, int y_end);

// Sub-cell peak position from the 3-point parabolas in x and y (eq. 5.17).
GridPx interpolatePeak(const float* score, int width, int x, int y);

}  // namespace dv

#pragma once
// Peaks of the blob score found inside the banded pass (band_plan.h), while
// a band's score rows are still in cache, instead of a second read of the
// whole score plane. A row's 4-way test needs the rows above and below, so
// a band tests its inner rows as it scores them and leaves its first and
// last rows (whose neighbours belong to the bands beside it) for after the
// pass. Each list keeps the cells in row order, as findPeakRows would, so
// the blobs come out the same. Storage is reserved once per camera.
#include <vector>

#include "pipeline/blob.h"
#include "pipeline/peak_select.h"

namespace dv {

struct BandPeaks {
  // Ratio (score / gradient energy) not computed yet.
  static constexpr float kRatioPending = -1;
  struct List {
    std::vector<PeakCandidate> peaks;  // raw score
    std::vector<float> ratio;          // per peak, or kRatioPending
    int n = 0;
  };
  List first, inner, last;  // the band's first row, its inner rows, its last row
  // A list ran out of room, so peaks may be missing: the caller must scan
  // the score plane instead.
  bool full = false;
  // The blobs of the candidates that passed the ratio test, in list order
  // (position, ratio, color), with their cells and ratios: made on the
  // pool, so the serial selection after it only checks spacing and
  // saturation. The same for the weak peaks near the blobs kept
  // (`weak_raw`: candidates before the ratio test). More blobs than there
  // is room for also set `full`.
  std::vector<Blob> blobs, weak;
  std::vector<PeakCandidate> blob_cells, weak_cells;
  int blob_n = 0, weak_n = 0, weak_raw = 0;

  // capacity: peaks of the inner rows; width: the grid's (a row holds
  // fewer); blob_capacity: blobs of either kind.
  void reserve(int capacity, int width, int blob_capacity);
  void clear() { first.n = inner.n = last.n = blob_n = weak_n = weak_raw = 0, full = false; }
  // Appends the peaks of row y (findPeakRows' test) to `list`, ratios
  // pending; returns the index of the first one added.
  int scanRow(List& list, const float* score, const uint8_t* mask, int width, int height, int margin,
              float threshold, int y);
};

}  // namespace dv

#include "pipeline/band_peaks.h"

namespace dv {

void BandPeaks::reserve(int capacity, int width, int blob_capacity) {
  inner.peaks.resize(capacity), inner.ratio.resize(capacity);
  // At most every other cell of a row is a 4-way maximum.
  for (List* l : {&first, &last}) l->peaks.resize(width / 2 + 1), l->ratio.resize(width / 2 + 1);
  for (auto* v : {&blobs, &weak}) v->resize(blob_capacity);
  for (auto* v : {&blob_cells, &weak_cells}) v->resize(blob_capacity);
  clear();
}

int BandPeaks::scanRow(List& list, const float* score, const uint8_t* mask, int width, int height, int margin,
                       float threshold, int y) {
  const int from = list.n;
  const int capacity = static_cast<int>(list.peaks.size());
  list.n = findPeakRows(score, mask, width, height, margin, threshold, list.peaks.data(), from, capacity, y, y + 1);
  if (list.n >= capacity) full = true;  // findPeakRows stops silently when full
  for (int i = from; i < list.n; ++i) list.ratio[i] = kRatioPending;
  return from;
}

}  // namespace dv

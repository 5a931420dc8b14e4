#include "pipeline/band_plan.h"

#include <algorithm>
#include <cmath>

namespace dv {

BandPlan BandPlan::build(const RemapTable& table, bool transposed, int count, int reach) {
  BandPlan plan;
  plan.reach = reach;
  const int h = table.height, w = table.width;
  count = std::clamp(count, 1, std::max(1, h));
  // Band heights fall linearly from 3/2 to 1/2 of the mean: the pool hands
  // bands out in order, so the last ones, which decide how long one thread
  // waits for the other at the end of the pass, are the short ones.
  std::vector<int> edges(count + 1, 0);
  {
    double at = 0;
    const double mean = static_cast<double>(h) / count;
    for (int c = 0; c < count; ++c) {
      const double weight = count > 1 ? 1.5 - static_cast<double>(c) / (count - 1) : 1.0;
      at += weight * mean;
      edges[c + 1] = std::clamp(static_cast<int>(std::lround(at)), edges[c], h);
    }
    edges[count] = h;
  }
  size_t cells = 0;
  for (int c = 0; c < count; ++c) {
    Band b;
    b.y_begin = edges[c];
    b.y_end = edges[c + 1];
    b.lo = std::max(0, b.y_begin - reach);
    b.hi = std::min(h, b.y_end + reach);
    b.index_offset = cells;
    cells += static_cast<size_t>(b.hi - b.lo) * w;
    plan.bands.push_back(b);
  }
  plan.index.resize(cells);
  const int sw = table.src_width;
  for (Band& b : plan.bands) {
    // Bounding box of the 2x2 samples read, in table order (tx along a row).
    int tx0 = sw, tx1 = 0, ty0 = table.src_height, ty1 = 0;
    const size_t k0 = static_cast<size_t>(b.lo) * w, k1 = static_cast<size_t>(b.hi) * w;
    for (size_t k = k0; k < k1; ++k) {
      const int tx = table.index[k] % sw, ty = table.index[k] / sw;
      tx0 = std::min(tx0, tx), tx1 = std::max(tx1, tx + 2);
      ty0 = std::min(ty0, ty), ty1 = std::max(ty1, ty + 2);
    }
    // Rows of whole 64-byte lines; a stride of a power of two would put
    // every row in the same cache set.
    b.stride = (tx1 - tx0 + 15) / 16 * 16 + 16;
    plan.box_size = std::max(plan.box_size, static_cast<size_t>(b.stride) * (ty1 - ty0));
    for (size_t k = k0; k < k1; ++k) {
      const int tx = table.index[k] % sw, ty = table.index[k] / sw;
      plan.index[b.index_offset + (k - k0)] = (ty - ty0) * b.stride + (tx - tx0);
    }
    if (transposed) b.i_begin = ty0, b.i_end = ty1, b.j_begin = tx0, b.j_end = tx1;
    else b.i_begin = tx0, b.i_end = tx1, b.j_begin = ty0, b.j_end = ty1;
  }
  return plan;
}

}  // namespace dv

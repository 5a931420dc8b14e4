#include <cstring>

#include "pipeline/kernels.h"

namespace dv {

void satRowPrefixRows(const int32_t* g, int width, int height, uint32_t* sat, int y_begin,
                      int y_end) {
  const size_t stride = static_cast<size_t>(width) + 1;
  for (int y = y_begin; y < y_end; ++y) {
    uint32_t* out = sat + (y + 1) * stride;
    out[0] = 0;
    if (y + 1 >= height) {  // the last row has no 2x2 box
      for (int x = 0; x < width; ++x) out[x + 1] = 0;
      continue;
    }
    const int32_t* r0 = g + static_cast<size_t>(y) * width;
    const int32_t* r1 = r0 + width;
    uint32_t acc = 0;
    for (int x = 0; x + 1 < width; ++x) {
      acc += static_cast<uint32_t>(r0[x]) + static_cast<uint32_t>(r0[x + 1]) +
             static_cast<uint32_t>(r1[x]) + static_cast<uint32_t>(r1[x + 1]);
      out[x + 1] = acc;
    }
    out[width] = acc;
  }
}

__attribute__((target_clones("avx2", "default"))) void satColumnPrefix(uint32_t* sat, int width,
                                                                       int height, int x_begin,
                                                                       int x_end) {
  const size_t stride = static_cast<size_t>(width) + 1;
  for (int y = 2; y <= height; ++y) {
    uint32_t* row = sat + y * stride;
    const uint32_t* prev = row - stride;
    for (int x = x_begin; x < x_end; ++x) row[x] += prev[x];
  }
}

}  // namespace dv

// Stage 5: blob score (thesis eq. 5.15, §5.2.7.3), as pipeline/blob_score.cpp.
// The table holds 2x2 box sums at half-cell offsets, so the quadrants of cell
// (x, y) are box columns [x-r, x) / [x, x+r) and rows [y-r, y) / [y, y+r),
// each without its inner q x q corner next to the center (field-line
// crossings respond there, blobs on their rim). Quadrant sums are exact
// integers; the score is the minimum of the two positive-diagonal sums and the
// negated anti-diagonal sums times `norm` = 1 / (4 * 16384 (r^2 - q^2)).
// Cells without a full window are 0.
//
// min(-tr, -bl) is written as -max(tr, bl): NVIDIA's OpenCL compiler (driver
// 580) dropped the bottom-left term of the former.
#pragma OPENCL FP_CONTRACT OFF

__kernel void score_quadrant_min(__global const uint* sat, int width, int height, int r, int q,
                                 float norm, __global float* score) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const int m = r + 1;
  if (y < m || y >= height - m || width <= 2 * m || x < m || x >= width - m) {
    score[(size_t)y * width + x] = 0.0f;
    return;
  }
  const size_t stride = (size_t)width + 1;
  __global const uint* s_top = sat + (size_t)(y - r) * stride;
  __global const uint* s_mid = sat + (size_t)y * stride;
  __global const uint* s_bot = sat + (size_t)(y + r) * stride;
  __global const uint* s_itop = sat + (size_t)(y - q) * stride;
  __global const uint* s_ibot = sat + (size_t)(y + q) * stride;
  const uint c = s_mid[x];
  const uint top_r = s_top[x - r], top_0 = s_top[x], top_p = s_top[x + r];
  const uint mid_r = s_mid[x - r], mid_p = s_mid[x + r], mid_qm = s_mid[x - q], mid_qp = s_mid[x + q];
  const uint bot_r = s_bot[x - r], bot_0 = s_bot[x], bot_p = s_bot[x + r];
  const uint it_q = s_itop[x - q], it_0 = s_itop[x], it_p = s_itop[x + q];
  const uint ib_q = s_ibot[x - q], ib_0 = s_ibot[x], ib_p = s_ibot[x + q];
  const int tl = as_int((c - top_0 - mid_r + top_r) - (c - it_0 - mid_qm + it_q));
  const int tr = as_int((mid_p - top_p - c + top_0) - (mid_qp - it_p - c + it_0));
  const int bl = as_int((bot_0 - c - bot_r + mid_r) - (ib_0 - c - ib_q + mid_qm));
  const int br = as_int((bot_p - mid_p - bot_0 + c) - (ib_p - mid_qp - ib_0 + c));
  const int lo = min(min(tl, br), -max(tr, bl));
  score[(size_t)y * width + x] = convert_float(lo) * norm;
}

// Exact quarter discs from the row prefix sums only (no column pass):
// half_width[j] is the half-width of box row offset j = 1..nrows,
// norm = 1 / (4 * 16384 n) for n box cells per quarter disc.
__kernel void score_circle_min(__global const uint* row_prefix, int width, int height,
                               __constant int* half_width, int nrows, float norm,
                               __global float* score) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const int m = nrows + 1;
  if (y < m || y >= height - m || width <= 2 * m || x < m || x >= width - m) {
    score[(size_t)y * width + x] = 0.0f;
    return;
  }
  const size_t stride = (size_t)width + 1;
  uint tl = 0u, tr = 0u, bl = 0u, br = 0u;
  for (int j = 1; j <= nrows; ++j) {
    const int h = half_width[j];
    if (h == 0) continue;
    __global const uint* up = row_prefix + (size_t)(y - j + 1) * stride;  // box row y-j
    __global const uint* dn = row_prefix + (size_t)(y + j) * stride;      // box row y+j-1
    tl += up[x] - up[x - h];
    tr += up[x + h] - up[x];
    bl += dn[x] - dn[x - h];
    br += dn[x + h] - dn[x];
  }
  const int lo = min(min(as_int(tl), as_int(br)), -max(as_int(tr), as_int(bl)));
  score[(size_t)y * width + x] = convert_float(lo) * norm;
}

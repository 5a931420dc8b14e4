// Stage 5: blob score (thesis eq. 5.15, §5.2.7.3), as pipeline/blob_score.cpp.
// Quadrant sums are exact integers from the table; the minimum of the two
// positive-diagonal sums and the negated anti-diagonal sums, scaled by `norm`
// = 1 / (65536 r^2). Cells without a full window are 0.
#pragma OPENCL FP_CONTRACT OFF

__kernel void score_quadrant_min(__global const uint* sat, int width, int height, int r,
                                 float norm, __global float* score) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const int m = r + 1;
  if (y < m || y >= height - m || width <= 2 * m || x < m || x >= width - m) {
    score[(size_t)y * width + x] = 0.0f;
    return;
  }
  const size_t stride = (size_t)width + 1;
  // Table rows y-r (rows < y-r), y, y+1 and y+r+1; columns x-r, x, x+1, x+r+1.
  const size_t t0 = (size_t)(y - r) * stride, t1 = (size_t)y * stride, t2 = t1 + stride,
               t3 = (size_t)(y + r + 1) * stride;
  const uint a0 = sat[t0 + x - r], a1 = sat[t0 + x], a2 = sat[t0 + x + 1], a3 = sat[t0 + x + r + 1];
  const uint b0 = sat[t1 + x - r], b1 = sat[t1 + x], b2 = sat[t1 + x + 1], b3 = sat[t1 + x + r + 1];
  const uint c0 = sat[t2 + x - r], c1 = sat[t2 + x], c2 = sat[t2 + x + 1], c3 = sat[t2 + x + r + 1];
  const uint d0 = sat[t3 + x - r], d1 = sat[t3 + x], d2 = sat[t3 + x + 1], d3 = sat[t3 + x + r + 1];
  const int tl = as_int(b1 - a1 - b0 + a0);
  const int tr = as_int(b3 - a3 - b2 + a2);
  const int bl = as_int(d1 - c1 - d0 + c0);
  const int br = as_int(d3 - c3 - d2 + c2);
  // Written as -max rather than min(-tr, -bl): NVIDIA's OpenCL compiler
  // (driver 580) dropped the bottom-left term of the latter form.
  const int lo = min(min(tl, br), -max(tr, bl));
  score[(size_t)y * width + x] = convert_float(lo) * norm;
}

// Exact quarter discs from the row prefix sums only (no column pass):
// half_width[j] is the half-width of row offset j = 1..nrows, norm = 1/(65536 n).
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
    __global const uint* up = row_prefix + (y - j + 1) * stride;
    __global const uint* dn = row_prefix + (y + j + 1) * stride;
    tl += up[x] - up[x - h];
    tr += up[x + h + 1] - up[x + 1];
    bl += dn[x] - dn[x - h];
    br += dn[x + h + 1] - dn[x + 1];
  }
  const int lo = min(min(as_int(tl), as_int(br)), -max(as_int(tr), as_int(bl)));
  score[(size_t)y * width + x] = convert_float(lo) * norm;
}

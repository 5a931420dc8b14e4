// Stage 1: Bayer 2x2 subsampling into an RGBX image (thesis §5.2.3), the same
// integer arithmetic as the CPU reference (pipeline/bayer_subsample.cpp): green
// is the mean of the two green sites, red and blue are moved a quarter cell to
// the cell center with bilinear weights 9:3:3:1 (/16), borders repeat.
// Fused here: the sparse frame brightness sum (every 16th row, every 4th
// column of the RGBX image) that sets the chroma normalisation floor, so it
// costs no extra pass over memory. Needs a 16x16 work-group.

#define DV_LUMA_GROUP 256

inline uint dv_quarter_shift(uint c, uint nx, uint ny, uint nxy) {
  return (9u * c + 3u * nx + 3u * ny + nxy + 8u) >> 4;
}

// Work-group sum of `v`, added once per group to *acc.
inline void dv_group_add(uint v, __local uint* scratch, volatile __global uint* results) {
  const int lid = get_local_id(1) * get_local_size(0) + get_local_id(0);
  const int n = get_local_size(0) * get_local_size(1);
  scratch[lid] = v;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int s = n / 2; s > 0; s >>= 1) {
    if (lid < s) scratch[lid] += scratch[lid + s];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0 && scratch[0] != 0u) atomic_add(&results[DV_RESULT_LUMA_SUM], scratch[0]);
}

__kernel void bayer_subsample(__global const uchar* raw, int raw_stride, int ws, int hs,
                              int rx, int ry, int bx, int by, __global uchar4* rgbx,
                              volatile __global uint* results) {
  __local uint scratch[DV_LUMA_GROUP];
  const int i = get_global_id(0), j = get_global_id(1);
  uint luma = 0;
  if (i < ws && j < hs) {
    const int last = ws - 1;
    const int rj = clamp(j + (ry == 0 ? 1 : -1), 0, hs - 1);
    const int bj = clamp(j + (by == 0 ? 1 : -1), 0, hs - 1);
    __global const uchar* r_row = raw + (size_t)(2 * j + ry) * raw_stride;
    __global const uchar* r_nrow = raw + (size_t)(2 * rj + ry) * raw_stride;
    __global const uchar* b_row = raw + (size_t)(2 * j + by) * raw_stride;
    __global const uchar* b_nrow = raw + (size_t)(2 * bj + by) * raw_stride;
    __global const uchar* g_row1 = raw + (size_t)(2 * j + 1 - ry) * raw_stride;
    const int rc = 2 * i + rx, bc = 2 * i + bx;
    const int rn = clamp(rc + (rx == 0 ? 2 : -2), rx, 2 * last + rx);
    const int bn = clamp(bc + (bx == 0 ? 2 : -2), bx, 2 * last + bx);
    const uint r = dv_quarter_shift(r_row[rc], r_row[rn], r_nrow[rc], r_nrow[rn]);
    const uint g = ((uint)r_row[2 * i + 1 - rx] + (uint)g_row1[2 * i + rx] + 1u) >> 1;
    const uint b = dv_quarter_shift(b_row[bc], b_row[bn], b_nrow[bc], b_nrow[bn]);
    rgbx[(size_t)j * ws + i] = (uchar4)((uchar)r, (uchar)g, (uchar)b, (uchar)0);
    if ((j & 15) == 0 && (i & 3) == 0) luma = r + g + b;
  }
  dv_group_add(luma, scratch, results);
}

// BGR 8UC3 input: no subsampling, only the reorder to RGBX and the brightness sum.
__kernel void bgr_to_rgbx(__global const uchar* bgr, int bgr_stride, int ws, int hs,
                          __global uchar4* rgbx, volatile __global uint* results) {
  __local uint scratch[DV_LUMA_GROUP];
  const int i = get_global_id(0), j = get_global_id(1);
  uint luma = 0;
  if (i < ws && j < hs) {
    __global const uchar* p = bgr + (size_t)j * bgr_stride + 3 * i;
    const uchar4 v = (uchar4)(p[2], p[1], p[0], (uchar)0);
    rgbx[(size_t)j * ws + i] = v;
    if ((j & 15) == 0 && (i & 3) == 0) luma = (uint)v.x + v.y + v.z;
  }
  dv_group_add(luma, scratch, results);
}

// Stage 1: Bayer 2x2 subsampling straight to packed chroma (thesis §5.2.3,
// §5.2.5), the same integer arithmetic as the CPU reference
// (pipeline/bayer_subsample.cpp, bayerChromaRows): green is the mean of the
// two green sites, red and blue are moved a quarter cell to the cell center
// with bilinear weights 9:3:3:1 (/16), borders repeat; the two chroma values
// use coefficients in 1/1024 (>> 4, so chroma x 64) and are packed as int16
// pairs (a in the low half).
// Fused here: the sparse frame brightness sum over the region the grid reads
// (every 16th sample row, every 4th sample column from its corner), which sets
// the exposure normalisation, so it costs no extra pass. Needs a work-group
// whose size is a power of two (at most 256).

#define DV_LUMA_GROUP 256

inline uint dv_pack_chroma(int4 ka, int4 kb, int r, int g, int b) {
  const int a = (ka.x * r + ka.y * g + ka.z * b + 8) >> 4;
  const int c = (kb.x * r + kb.y * g + kb.z * b + 8) >> 4;
  return ((uint)a & 0xffffu) | ((uint)c << 16);
}

// Work-group sum of `v`, added once per group to the results' brightness sum.
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

// region = (x_begin, x_end, y_begin, y_end) of the samples the grid reads.
__kernel void bayer_chroma(__global const uchar* raw, int raw_stride, int ws, int hs, int rx,
                           int ry, int bx, int by, int4 ka, int4 kb, int4 region,
                           __global uint* packed, volatile __global uint* results) {
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
    const int r = dv_quarter_shift(r_row[rc], r_row[rn], r_nrow[rc], r_nrow[rn]);
    const int g = ((int)r_row[2 * i + 1 - rx] + (int)g_row1[2 * i + rx] + 1) >> 1;
    const int b = dv_quarter_shift(b_row[bc], b_row[bn], b_nrow[bc], b_nrow[bn]);
    packed[(size_t)j * ws + i] = dv_pack_chroma(ka, kb, r, g, b);
    if (i >= region.x && i < region.y && j >= region.z && j < region.w &&
        ((j - region.z) & 15) == 0 && ((i - region.x) & 3) == 0) {
      // The cell's raw sites, unshifted: twice red and blue, once each green.
      __global const uchar* r0 = raw + (size_t)(2 * j) * raw_stride + 2 * i;
      __global const uchar* r1 = r0 + raw_stride;
      const int all = r0[0] + r0[1] + r1[0] + r1[1];
      const int rr = r_row[rc], bb = b_row[bc];
      luma = (uint)(2 * (rr + bb) + (all - rr - bb));
    }
  }
  dv_group_add(luma, scratch, results);
}

// Full Bayer sampling (pipeline/bayer_full.h): a sample per pixel, the 2x2
// window at each pixel treated as a cell above. The brightness sum is the
// subsampling's, over the 2x2 cells under the samples read: `cells` is that
// region in cells (fullBayerCells), visited at its even pixels.
__kernel void bayer_full_chroma(__global const uchar* raw, int raw_stride, int w, int h, int4 sites,
                                int4 ka, int4 kb, int4 cells, __global uint* packed,
                                volatile __global uint* results) {
  __local uint scratch[DV_LUMA_GROUP];
  const int x = get_global_id(0), y = get_global_id(1);
  uint luma = 0;
  if (x < w && y < h) {
    const int3 c = dv_window_rgb(raw, raw_stride, w, h, sites, x, y);
    packed[(size_t)y * w + x] = dv_pack_chroma(ka, kb, c.x, c.y, c.z);
    const int i = x >> 1, j = y >> 1;
    if (((x | y) & 1) == 0 && i >= cells.x && i < cells.y && j >= cells.z && j < cells.w &&
        ((j - cells.z) & 15) == 0 && ((i - cells.x) & 3) == 0) {
      __global const uchar* r0 = raw + (size_t)y * raw_stride + x;
      __global const uchar* r1 = r0 + raw_stride;
      const int all = r0[0] + r0[1] + r1[0] + r1[1];
      const int rr = raw[(size_t)(y + sites.y) * raw_stride + x + sites.x];
      const int bb = raw[(size_t)(y + sites.w) * raw_stride + x + sites.z];
      luma = (uint)(2 * (rr + bb) + (all - rr - bb));
    }
  }
  dv_group_add(luma, scratch, results);
}

// BGR 8UC3 input: no subsampling, only the chroma and the brightness sum.
__kernel void bgr_chroma(__global const uchar* bgr, int bgr_stride, int ws, int hs, int4 ka,
                         int4 kb, int4 region, __global uint* packed,
                         volatile __global uint* results) {
  __local uint scratch[DV_LUMA_GROUP];
  const int i = get_global_id(0), j = get_global_id(1);
  uint luma = 0;
  if (i < ws && j < hs) {
    __global const uchar* p = bgr + (size_t)j * bgr_stride + 3 * i;
    packed[(size_t)j * ws + i] = dv_pack_chroma(ka, kb, p[2], p[1], p[0]);
    if (i >= region.x && i < region.y && j >= region.z && j < region.w &&
        ((j - region.z) & 15) == 0 && ((i - region.x) & 3) == 0)
      luma = (uint)p[0] + p[1] + p[2];
  }
  dv_group_add(luma, scratch, results);
}

// Shared by all kernel files; placed first in the program.
//
// Layout of the small results buffer the stages share: counters first, then
// the peak records of peaks.cl. The host reads the counters and the first
// peaks back in one transfer.
#define DV_RESULT_PEAK_COUNT 0
#define DV_RESULT_LUMA_SUM 1
#define DV_RESULT_LUMA_MEAN 2
#define DV_RESULT_HEADER 4

// The gradient dot product's fixed point (pipeline/kernels.h).
#define DV_GRADIENT_FIXED_POINT 16384.0f

// Bilinear weights 9:3:3:1 (/16) move a Bayer site half a pixel toward its
// neighbours of the same color (pipeline/bayer_subsample.h, quarterShift).
inline int dv_quarter_shift(int c, int nx, int ny, int nxy) {
  return (9 * c + 3 * nx + 3 * ny + nxy + 8) >> 4;
}

// Full Bayer sampling (pipeline/bayer_full.cpp): RGB of the 2x2 window whose
// top-left pixel is (x, y), co-sited at (x + 1/2, y + 1/2). A site beyond
// the image edge is the one two pixels back (same color). Used by the first
// stage and by the blob colors of the peak stage.
inline int dv_reflect(int c, int n) { return c < 0 ? c + 2 : (c >= n ? c - 2 : c); }

inline int3 dv_window_rgb(__global const uchar* raw, int stride, int w, int h, int4 sites, int x,
                          int y) {
#define DV_PX(cx, cy) ((int)raw[(size_t)dv_reflect(cy, h) * stride + dv_reflect(cx, w)])
  // Red (sites.xy) and blue (sites.zw): the window's site and the next one of
  // its color across the window center, in x and in y.
  int cx = x + ((sites.x - x) & 1), cy = y + ((sites.y - y) & 1);
  int nx = cx == x ? cx + 2 : cx - 2, ny = cy == y ? cy + 2 : cy - 2;
  const int r = dv_quarter_shift(DV_PX(cx, cy), DV_PX(nx, cy), DV_PX(cx, ny), DV_PX(nx, ny));
  cx = x + ((sites.z - x) & 1), cy = y + ((sites.w - y) & 1);
  nx = cx == x ? cx + 2 : cx - 2, ny = cy == y ? cy + 2 : cy - 2;
  const int b = dv_quarter_shift(DV_PX(cx, cy), DV_PX(nx, cy), DV_PX(cx, ny), DV_PX(nx, ny));
  // Greens: on a red row at the other column parity than red, on a blue row
  // at red's.
  const int g0 = ((y - sites.y) & 1) == 0 ? 1 - sites.x : sites.x;
  const int g = (DV_PX(x + ((g0 - x) & 1), y) + DV_PX(x + ((1 - g0 - x) & 1), y + 1) + 1) >> 1;
#undef DV_PX
  return (int3)(r, g, b);
}

// The color gradients of cell (x, y) at scale k + a (linear between samples
// k and k + 1 away), as gradientRow in pipeline/blob_score.cpp:
// (gx, gy) of chroma channel a, then of channel b.
inline float4 dv_cell_gradient(__global const float2* chroma, size_t w, int k, float a, float na, int x, int y) {
  __global const float2* mid = chroma + y * w;
  const float2 xp = mid[x + k], xm = mid[x - k], xp1 = mid[x + k + 1], xm1 = mid[x - k - 1];
  const float2 yp = chroma[(y + k) * w + x], ym = chroma[(y - k) * w + x];
  const float2 yp1 = chroma[(y + k + 1) * w + x], ym1 = chroma[(y - k - 1) * w + x];
  return (float4)(na * (xp.x - xm.x) + a * (xp1.x - xm1.x), na * (yp.x - ym.x) + a * (yp1.x - ym1.x),
                  na * (xp.y - xm.y) + a * (xp1.y - xm1.y), na * (yp.y - ym.y) + a * (yp1.y - ym1.y));
}

#ifdef DV_TEST_BUILD_FAILURE
#error "build failure requested by a test (DV_TEST_BUILD_FAILURE)"
#endif

// Stage 6: blob selection (thesis §5.2.8, §5.2.9), as pipeline/peak_select.cpp
// and CpuPipeline: 4-way local peaks of the raw score above `raw_threshold`
// (strict on the left/top, non-strict on the right/bottom, so a plateau gives
// one peak) where the peak mask allows; their reported score is the ratio of
// the raw score to (mean gradient energy in the window + floor), kept above
// `threshold` (the weak threshold where weak peaks are wanted: the host
// tells blobs from weak peaks by the ratio); then quadratic peak
// interpolation on the raw score and the mean bilinear RGB over the disc of
// `color_radius` cells, read from the raw frame (co-sited samples, as sampleRgbAt in pipeline/bayer_subsample.cpp
// or fullBayerRgbAt in pipeline/bayer_full.cpp). Peaks are appended to a
// compact list (after the counters of the results buffer) through an
// atomic counter; the host orders them by score.
#pragma OPENCL FP_CONTRACT OFF

#ifdef DV_FP64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double dv_real;  // the CPU reference does the disc test in double
#else
typedef float dv_real;
#endif

// x, y: interpolated position; cell_x, cell_y: the peak cell (the host's
// duplicate test uses it, as the CPU reference does).
typedef struct {
  float x, y, score, r, g, b, cell_x, cell_y;
} dv_peak;

// Stores a peak in slot `slot` of a list kept after the results header.
inline void dv_store_peak(__global uint* list, uint slot, float x, float y, float score, int cell_x,
                          int cell_y, float3 rgb) {
  dv_peak p;
  p.x = x;
  p.y = y;
  p.score = score;
  p.cell_x = cell_x;
  p.cell_y = cell_y;
  p.r = rgb.x;
  p.g = rgb.y;
  p.b = rgb.z;
  ((__global dv_peak*)(list + DV_RESULT_HEADER))[slot] = p;
}

inline float dv_peak_offset(float l, float c, float r) {
  const float d = l - 2 * c + r;
  if (!(d < 0)) return 0.0f;
  return clamp(0.5f * (l - r) / d, -0.5f, 0.5f);
}

// Mean gradient energy 1/2 sum_c (gx^2 + gy^2) over the (2r+1)^2 window,
// the same gradient and summation order as windowGradientEnergy
// (pipeline/gradient_dot.cpp): a float sum down each column, the columns
// added in double (where available). With an energy form q (view_stretch.h,
// not null) each cell's term is q's, as windowGradientEnergyForm.
inline float dv_window_energy(__global const float2* chroma, int width, int k, float a, float na,
                              int x, int y, int r, __global const float* q) {
  const size_t w = width;
  const float qxx = q ? q[0] : 0, qxy2 = q ? 2 * q[1] : 0, qyy = q ? q[2] : 0;
  dv_real sum = 0;
  for (int xx = x - r; xx <= x + r; ++xx) {
    float col = 0;
    for (int yy = y - r; yy <= y + r; ++yy) {
      const float4 g = dv_cell_gradient(chroma, w, k, a, na, xx, yy);
      const float gxa = g.x, gya = g.y, gxb = g.z, gyb = g.w;
      col += q ? qxx * (gxa * gxa + gxb * gxb) + qxy2 * (gxa * gya + gxb * gyb) + qyy * (gya * gya + gyb * gyb)
               : gxa * gxa + gya * gya + gxb * gxb + gyb * gyb;
    }
    sum += (dv_real)col;
  }
  return (float)((dv_real)0.5 * sum / (dv_real)((2 * r + 1) * (2 * r + 1)));
}

// Co-sited RGB of sample (i, j), clamped to the image: BGR (bayer 0),
// subsampled Bayer (1, sites rx, ry, bx, by) or full Bayer sampling (2).
inline float3 dv_sample_rgb(__global const uchar* raw, int stride, int bayer, int4 sites, int ws,
                            int hs, int i, int j) {
  i = clamp(i, 0, ws - 1);
  j = clamp(j, 0, hs - 1);
  if (bayer == 2) return convert_float3(dv_window_rgb(raw, stride, ws, hs, sites, i, j));
  if (!bayer) {
    __global const uchar* p = raw + (size_t)j * stride + 3 * i;
    return (float3)(p[2], p[1], p[0]);
  }
  const int rx = sites.x, ry = sites.y, bx = sites.z, by = sites.w;
#define DV_AT(x, y) ((int)raw[(size_t)(y) * stride + (x)])
  int ni = clamp(i + (rx == 0 ? 1 : -1), 0, ws - 1), nj = clamp(j + (ry == 0 ? 1 : -1), 0, hs - 1);
  const int r = (9 * DV_AT(2 * i + rx, 2 * j + ry) + 3 * DV_AT(2 * ni + rx, 2 * j + ry) +
                 3 * DV_AT(2 * i + rx, 2 * nj + ry) + DV_AT(2 * ni + rx, 2 * nj + ry) + 8) >> 4;
  ni = clamp(i + (bx == 0 ? 1 : -1), 0, ws - 1);
  nj = clamp(j + (by == 0 ? 1 : -1), 0, hs - 1);
  const int b = (9 * DV_AT(2 * i + bx, 2 * j + by) + 3 * DV_AT(2 * ni + bx, 2 * j + by) +
                 3 * DV_AT(2 * i + bx, 2 * nj + by) + DV_AT(2 * ni + bx, 2 * nj + by) + 8) >> 4;
  const int g = (DV_AT(2 * i + 1 - rx, 2 * j + ry) + DV_AT(2 * i + rx, 2 * j + 1 - ry) + 1) >> 1;
#undef DV_AT
  return (float3)(r, g, b);
}

// Mean color of the grid cells within `rad` of (px, py), each sampled
// bilinearly from the co-sited samples as the CPU's meanColor does; 0 where
// no cell is inside.
inline float3 dv_disc_mean_rgb(__global const uchar* raw, int raw_stride, int bayer, int4 sites,
                               int src_width, int src_height, __global const int* remap_index,
                               __global const ushort* remap_frac, int width, int height, dv_real px,
                               dv_real py, dv_real rad) {
  const int x0 = max(0, (int)ceil(px - rad)), x1 = min(width - 1, (int)floor(px + rad));
  const int y0 = max(0, (int)ceil(py - rad)), y1 = min(height - 1, (int)floor(py + rad));
  float3 sum = (float3)(0.0f, 0.0f, 0.0f);
  int n = 0;
  for (int yy = y0; yy <= y1; ++yy) {
    for (int xx = x0; xx <= x1; ++xx) {
      if ((xx - px) * (xx - px) + (yy - py) * (yy - py) > rad * rad) continue;
      const size_t kk = (size_t)yy * width + xx;
      const int i = remap_index[kk];
      const uint fr = remap_frac[kk];
      const int sx = i % src_width, sy = i / src_width;
      const float fx = (float)(fr & 255u) / 256.0f, fy = (float)(fr >> 8) / 256.0f;
      const float w0 = (1 - fx) * (1 - fy), w1 = fx * (1 - fy), w2 = (1 - fx) * fy, w3 = fx * fy;
      const float3 p0 = dv_sample_rgb(raw, raw_stride, bayer, sites, src_width, src_height, sx, sy);
      const float3 p1 = dv_sample_rgb(raw, raw_stride, bayer, sites, src_width, src_height, sx + 1, sy);
      const float3 p2 = dv_sample_rgb(raw, raw_stride, bayer, sites, src_width, src_height, sx, sy + 1);
      const float3 p3 = dv_sample_rgb(raw, raw_stride, bayer, sites, src_width, src_height, sx + 1, sy + 1);
      sum.x += w0 * p0.x + w1 * p1.x + w2 * p2.x + w3 * p3.x;
      sum.y += w0 * p0.y + w1 * p1.y + w2 * p2.y + w3 * p3.y;
      sum.z += w0 * p0.z + w1 * p1.z + w2 * p2.z + w3 * p3.z;
      ++n;
    }
  }
  return n ? sum / (float)n : (float3)(0.0f, 0.0f, 0.0f);
}

__kernel void find_peaks(__global const float* score, __global const uchar* mask, int width,
                         int height, int margin, float raw_threshold, float threshold,
                         __global const float2* chroma, int k, float a, float na, int window,
                         float energy_floor, __global const uchar* raw, int raw_stride,
                         int bayer, int4 sites, int src_width, int src_height,
                         __global const int* remap_index,
                         __global const ushort* remap_frac, dv_real color_radius,
                         __global uint* results, int capacity, __global const float* forms,
                         __global const uchar* form_plain, int form_block, int form_blocks_x,
                         int use_forms) {
  const int x = get_global_id(0), y = get_global_id(1);
  // The brightness sum was consumed by the rectify stage; clear it for the next frame.
  if (x == 0 && y == 0) results[DV_RESULT_LUMA_SUM] = 0u;
  if (x < margin || y < margin || x >= width - margin || y >= height - margin) return;
  const size_t cell = (size_t)y * width + x;
  const float c = score[cell];
  if (!(c > raw_threshold)) return;
  const float l = score[cell - 1], rt = score[cell + 1], up = score[cell - width], dn = score[cell + width];
  if (!(c > l && c >= rt && c > up && c >= dn && mask[cell])) return;
  const int blk = (y / form_block) * form_blocks_x + x / form_block;
  const float energy = use_forms && !form_plain[blk]
                           ? dv_window_energy(chroma, width, k, a, na, x, y, window, forms + 6 * blk + 3)
                           : dv_window_energy(chroma, width, k, a, na, x, y, window, 0);
  const float ratio = c / (energy + energy_floor);
  if (!(ratio > threshold)) return;
  const uint slot = atomic_inc(&results[DV_RESULT_PEAK_COUNT]);
  if (slot >= (uint)capacity) return;

  const float gx = x + dv_peak_offset(l, c, rt);
  const float gy = y + dv_peak_offset(up, c, dn);
  const float3 rgb = dv_disc_mean_rgb(raw, raw_stride, bayer, sites, src_width, src_height, remap_index,
                                      remap_frac, width, height, gx, gy, color_radius);
  dv_store_peak(results, slot, gx, gy, ratio, x, y, rgb);
}

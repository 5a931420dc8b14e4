// Stage 6: blob selection (thesis §5.2.8, §5.2.9), as pipeline/peak_select.cpp
// and CpuPipeline's mean color: 4-way local peaks above the threshold (strict
// on the left/top, non-strict on the right/bottom, so a plateau gives one
// peak) where the peak mask allows, quadratic peak interpolation, and the mean
// bilinear RGB over the disc of `color_radius` cells. Peaks are appended to a
// compact list (after the counters of the results buffer) through an
// atomic counter; the host orders them by score.
#pragma OPENCL FP_CONTRACT OFF

#ifdef DV_FP64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double dv_real;  // the CPU reference does the disc test in double
#else
typedef float dv_real;
#endif

typedef struct {
  float x, y, score, r, g, b;
} dv_peak;

inline float dv_peak_offset(float l, float c, float r) {
  const float d = l - 2 * c + r;
  if (!(d < 0)) return 0.0f;
  return clamp(0.5f * (l - r) / d, -0.5f, 0.5f);
}

__kernel void find_peaks(__global const float* score, __global const uchar* mask, int width,
                         int height, int margin, float threshold, __global const uchar4* rgbx,
                         int src_width, __global const int* remap_index,
                         __global const ushort* remap_frac, dv_real color_radius,
                         __global uint* results, int capacity) {
  const int x = get_global_id(0), y = get_global_id(1);
  // The brightness sum was consumed by the rectify stage; clear it for the next frame.
  if (x == 0 && y == 0) results[DV_RESULT_LUMA_SUM] = 0u;
  if (x < margin || y < margin || x >= width - margin || y >= height - margin) return;
  const size_t k = (size_t)y * width + x;
  const float c = score[k];
  if (!(c > threshold)) return;
  const float l = score[k - 1], rt = score[k + 1], up = score[k - width], dn = score[k + width];
  if (!(c > l && c >= rt && c > up && c >= dn && mask[k])) return;
  const uint slot = atomic_inc(&results[DV_RESULT_PEAK_COUNT]);
  if (slot >= (uint)capacity) return;

  const float gx = x + dv_peak_offset(l, c, rt);
  const float gy = y + dv_peak_offset(up, c, dn);
  const dv_real rad = color_radius;
  const dv_real px = gx, py = gy;
  const int x0 = max(0, (int)ceil(px - rad)), x1 = min(width - 1, (int)floor(px + rad));
  const int y0 = max(0, (int)ceil(py - rad)), y1 = min(height - 1, (int)floor(py + rad));
  float sum_r = 0, sum_g = 0, sum_b = 0;
  int n = 0;
  for (int yy = y0; yy <= y1; ++yy) {
    for (int xx = x0; xx <= x1; ++xx) {
      if ((xx - px) * (xx - px) + (yy - py) * (yy - py) > rad * rad) continue;
      const size_t kk = (size_t)yy * width + xx;
      const int i = remap_index[kk];
      const uint fr = remap_frac[kk];
      const float fx = (float)(fr & 255u) / 256.0f, fy = (float)(fr >> 8) / 256.0f;
      const float w0 = (1 - fx) * (1 - fy), w1 = fx * (1 - fy), w2 = (1 - fx) * fy, w3 = fx * fy;
      const float4 p0 = convert_float4(rgbx[i]), p1 = convert_float4(rgbx[i + 1]);
      const float4 p2 = convert_float4(rgbx[i + src_width]), p3 = convert_float4(rgbx[i + src_width + 1]);
      float v;
      v = 0; v += w0 * p0.x; v += w1 * p1.x; v += w2 * p2.x; v += w3 * p3.x; sum_r += v;
      v = 0; v += w0 * p0.y; v += w1 * p1.y; v += w2 * p2.y; v += w3 * p3.y; sum_g += v;
      v = 0; v += w0 * p0.z; v += w1 * p1.z; v += w2 * p2.z; v += w3 * p3.z; sum_b += v;
      ++n;
    }
  }
  dv_peak p;
  p.x = gx;
  p.y = gy;
  p.score = c;
  p.r = n ? sum_r / n : 0.0f;
  p.g = n ? sum_g / n : 0.0f;
  p.b = n ? sum_b / n : 0.0f;
  ((__global dv_peak*)(results + DV_RESULT_HEADER))[slot] = p;
}

// Stage 2: rectification through the remap table (thesis §5.2.4), as
// pipeline/rectify_color.cpp: bilinear interpolation (1/256-sample fractions)
// of the packed int16 chroma pairs, times gain = 1 / (mean brightness * 64)
// (exposure normalisation; the brightness sum comes from the Bayer stage).
// Float operations are written in the CPU reference's order and contraction
// into FMA is off, so the results agree to the last bit where division is
// correctly rounded.
#pragma OPENCL FP_CONTRACT OFF

inline float dv_lo(uint p) { return (float)(short)(p & 0xffffu); }
inline float dv_hi(uint p) { return (float)(as_int(p) >> 16); }

__kernel void rectify_chroma(__global const uint* packed, int src_width,
                             __global const int* remap_index, __global const ushort* remap_frac,
                             int width, int height, float luma_count, float packed_scale,
                             __global uint* results, __global float2* chroma) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const float luma_mean = convert_float(results[DV_RESULT_LUMA_SUM]) / luma_count + 1.0f;
  const float gain = 1.0f / (luma_mean * packed_scale);
  if (x == 0 && y == 0) {
    // Peak extraction of this frame runs later in the same queue: reset its
    // counter; keep the mean for inspection.
    results[DV_RESULT_PEAK_COUNT] = 0u;
    results[DV_RESULT_LUMA_MEAN] = as_uint(luma_mean);
  }
  const size_t k = (size_t)y * width + x;
  const int i = remap_index[k];
  const uint fr = remap_frac[k];
  const float fx = (float)(fr & 255u) * (1.0f / 256.0f), fy = (float)(fr >> 8) * (1.0f / 256.0f);
  const float w11 = fx * fy, w01 = fx - w11, w10 = fy - w11, w00 = 1 - fx - fy + w11;
  const uint p00 = packed[i], p01 = packed[i + 1], p10 = packed[i + src_width],
             p11 = packed[i + src_width + 1];
  chroma[k] = (float2)((w00 * dv_lo(p00) + w01 * dv_lo(p01) + w10 * dv_lo(p10) + w11 * dv_lo(p11)) * gain,
                       (w00 * dv_hi(p00) + w01 * dv_hi(p01) + w10 * dv_hi(p10) + w11 * dv_hi(p11)) * gain);
}

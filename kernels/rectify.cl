// Stage 2: rectification through the remap table (thesis §5.2.4), as
// pipeline/rectify_color.cpp: exact integer bilinear interpolation
// (1/256-sample fractions) of the packed int16 chroma pairs, times
// gain / 2^16 with gain = 1 / (mean brightness * 64) (exposure normalisation;
// the brightness sum comes from the Bayer stage). One float product after
// exact integers, so the results agree to the last bit where division is
// correctly rounded.
#pragma OPENCL FP_CONTRACT OFF

inline int dv_lo(uint p) { return (int)(short)(p & 0xffffu); }
inline int dv_hi(uint p) { return as_int(p) >> 16; }

// Exact integer bilinear interpolation (weights in 1/256, x then y).
inline int dv_lerp2(int v00, int v01, int v10, int v11, int fx, int fy) {
  const int top = v00 * (256 - fx) + v01 * fx;
  const int bot = v10 * (256 - fx) + v11 * fx;
  return top * (256 - fy) + bot * fy;
}

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
  const int fx = (int)(fr & 255u), fy = (int)(fr >> 8);
  const uint p00 = packed[i], p01 = packed[i + 1], p10 = packed[i + src_width],
             p11 = packed[i + src_width + 1];
  const float scale = gain * (1.0f / 65536.0f);
  chroma[k] = (float2)((float)dv_lerp2(dv_lo(p00), dv_lo(p01), dv_lo(p10), dv_lo(p11), fx, fy) * scale,
                       (float)dv_lerp2(dv_hi(p00), dv_hi(p01), dv_hi(p10), dv_hi(p11), fx, fy) * scale);
}

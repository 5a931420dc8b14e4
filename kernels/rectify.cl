// Stage 2: rectification through the remap table (thesis §5.2.4) fused with
// the chroma transform (§5.2.5), as pipeline/rectify_color.cpp: bilinear RGB
// at 1/256-sample fractions, then two chroma channels divided by the frame's
// mean brightness (exposure normalisation; the sum comes from the Bayer stage).
// Float operations are written in the CPU reference's order and contraction
// into FMA is off, so the results agree to the last bit where division is
// correctly rounded.
#pragma OPENCL FP_CONTRACT OFF

__kernel void rectify_chroma(__global const uchar4* rgbx, int src_width,
                             __global const int* remap_index, __global const ushort* remap_frac,
                             int width, int height, float4 chroma_a, float4 chroma_b,
                             float luma_count,
                             __global uint* results, __global float2* chroma) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const float luma_mean = convert_float(results[DV_RESULT_LUMA_SUM]) / luma_count + 1.0f;
  const float gain = 1.0f / luma_mean;
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
  const float4 p00 = convert_float4(rgbx[i]), p01 = convert_float4(rgbx[i + 1]);
  const float4 p10 = convert_float4(rgbx[i + src_width]), p11 = convert_float4(rgbx[i + src_width + 1]);
  const float r = w00 * p00.x + w01 * p01.x + w10 * p10.x + w11 * p11.x;
  const float g = w00 * p00.y + w01 * p01.y + w10 * p10.y + w11 * p11.y;
  const float b = w00 * p00.z + w01 * p01.z + w10 * p10.z + w11 * p11.z;
  chroma[k] = (float2)((chroma_a.x * r + chroma_a.y * g + chroma_a.z * b) * gain,
                       (chroma_b.x * r + chroma_b.y * g + chroma_b.z * b) * gain);
}

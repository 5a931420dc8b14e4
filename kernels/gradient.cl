// Stage 3: color gradient dot product (thesis eq. 5.11, §5.2.7), as
// pipeline/gradient_dot.cpp: gradients `k + a` cells apart (fractional
// distances interpolate linearly), gx*gy summed over both chroma channels,
// stored in fixed point (x 16384, truncated, from chroma planes in 1/1024
// units: out_scale = 16384 / 1024^2) so that the summed-area table is exact
// integer arithmetic. Cells within the gradient
// reach of the border are 0.
#pragma OPENCL FP_CONTRACT OFF

__kernel void gradient_dot(__global const short2* chroma, int width, int height, int k, float a,
                           float na, float out_scale, __global int* gdot) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const int m = k + 1;
  const size_t w = width;
  if (y < m || y >= height - m || width <= 2 * m || x < m || x >= width - m) {
    gdot[y * w + x] = 0;
    return;
  }
  __global const short2* mid = chroma + y * w;
  const int2 xp = convert_int2(mid[x + k]), xm = convert_int2(mid[x - k]);
  const int2 xp1 = convert_int2(mid[x + k + 1]), xm1 = convert_int2(mid[x - k - 1]);
  const int2 yp = convert_int2(chroma[(y + k) * w + x]), ym = convert_int2(chroma[(y - k) * w + x]);
  const int2 yp1 = convert_int2(chroma[(y + k + 1) * w + x]), ym1 = convert_int2(chroma[(y - k - 1) * w + x]);
  const float gxa = na * (float)(xp.x - xm.x) + a * (float)(xp1.x - xm1.x);
  const float gya = na * (float)(yp.x - ym.x) + a * (float)(yp1.x - ym1.x);
  const float gxb = na * (float)(xp.y - xm.y) + a * (float)(xp1.y - xm1.y);
  const float gyb = na * (float)(yp.y - ym.y) + a * (float)(yp1.y - ym1.y);
  gdot[y * w + x] = convert_int_rtz((gxa * gya + gxb * gyb) * out_scale);
}

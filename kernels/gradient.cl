// Stage 3: color gradient dot product (thesis eq. 5.11, §5.2.7), as
// pipeline/gradient_dot.cpp: gradients `k + a` cells apart (fractional
// distances interpolate linearly), gx*gy summed over both chroma channels,
// stored in fixed point (x 16384, truncated toward zero) so that the
// summed-area table is exact integer arithmetic. Cells within the gradient
// reach of the border are 0.
#pragma OPENCL FP_CONTRACT OFF

// Where the view stretches blobs (pipeline/view_stretch.h) and the block
// row is not plain: the whitened product, the form (f0, f1, f2) of the
// cell's block: f0 gx^2 + f1 gx gy + f2 gy^2 summed over both channels.
__kernel void gradient_dot(__global const float2* chroma, int width, int height, int k, float a,
                           float na, __global int* gdot, __global const float* forms,
                           __global const uchar* plain_row, int block, int blocks_x, int use_forms) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const int m = k + 1;
  const size_t w = width;
  if (y < m || y >= height - m || width <= 2 * m || x < m || x >= width - m) {
    gdot[y * w + x] = 0;
    return;
  }
  __global const float2* mid = chroma + y * w;
  const float2 xp = mid[x + k], xm = mid[x - k], xp1 = mid[x + k + 1], xm1 = mid[x - k - 1];
  const float2 yp = chroma[(y + k) * w + x], ym = chroma[(y - k) * w + x];
  const float2 yp1 = chroma[(y + k + 1) * w + x], ym1 = chroma[(y - k - 1) * w + x];
  const float gxa = na * (xp.x - xm.x) + a * (xp1.x - xm1.x);
  const float gya = na * (yp.x - ym.x) + a * (yp1.x - ym1.x);
  const float gxb = na * (xp.y - xm.y) + a * (xp1.y - xm1.y);
  const float gyb = na * (yp.y - ym.y) + a * (yp1.y - ym1.y);
  if (use_forms && !plain_row[y / block]) {
    __global const float* f = forms + 6 * ((y / block) * blocks_x + x / block);
    const float v = f[0] * (gxa * gxa + gxb * gxb) + f[1] * (gxa * gya + gxb * gyb) + f[2] * (gya * gya + gyb * gyb);
    gdot[y * w + x] = convert_int_rtz(v * DV_GRADIENT_FIXED_POINT);
    return;
  }
  gdot[y * w + x] = convert_int_rtz((gxa * gya + gxb * gyb) * DV_GRADIENT_FIXED_POINT);
}

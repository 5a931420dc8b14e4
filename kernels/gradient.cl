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
  const float4 g = dv_cell_gradient(chroma, w, k, a, na, x, y);
  const float gxa = g.x, gya = g.y, gxb = g.z, gyb = g.w;
  if (use_forms && !plain_row[y / block]) {
    __global const float* f = forms + 6 * ((y / block) * blocks_x + x / block);
    const float v = f[0] * (gxa * gxa + gxb * gxb) + f[1] * (gxa * gya + gxb * gyb) + f[2] * (gya * gya + gyb * gyb);
    gdot[y * w + x] = convert_int_rtz(v * DV_GRADIENT_FIXED_POINT);
    return;
  }
  gdot[y * w + x] = convert_int_rtz((gxa * gya + gxb * gyb) * DV_GRADIENT_FIXED_POINT);
}

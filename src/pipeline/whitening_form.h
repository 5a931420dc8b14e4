#pragma once
// The per-block coefficients of the whitened gradient (view_stretch.h) for a
// stretch 1 + k along the unit grid direction (dx, dy). Plain C++ so that the
// stand-alone OpenCL benchmark can exercise the whitened kernels too.
namespace dv {

// c[0..2]: the product form (a, b, c) of G = (W g)_x (W g)_y = a gx^2 +
// b gx gy + c gy^2; c[3..5]: the energy form (qxx, qxy, qyy) of |W g|^2,
// with W = I + k d d^T (so W^T W = I + (2k + k^2) d d^T).
inline void whiteningForm(double k, double dx, double dy, float c[6]) {
  const double m1x = 1 + k * dx * dx, m1y = k * dx * dy;
  const double m2x = m1y, m2y = 1 + k * dy * dy;
  const double e = 2 * k + k * k;
  c[0] = static_cast<float>(m1x * m2x);
  c[1] = static_cast<float>(m1x * m2y + m1y * m2x);
  c[2] = static_cast<float>(m1y * m2y);
  c[3] = static_cast<float>(1 + e * dx * dx);
  c[4] = static_cast<float>(e * dx * dy);
  c[5] = static_cast<float>(1 + e * dy * dy);
}

}  // namespace dv

#include <algorithm>
#include <cmath>
#include <cstring>

#include "pipeline/kernels.h"
#include "pipeline/view_stretch.h"

namespace dv {

__attribute__((target_clones("avx2", "default"))) void gradientDotRowFrom(
    const float* const a_rows[5], const float* const b_rows[5], int width, double scale, int32_t* out) {
  // i(x + s) with s = k + a: linear between samples k and k + 1 away.
  const int k = static_cast<int>(std::floor(scale));
  const float a = static_cast<float>(scale - k), na = 1 - a;
  const int m = k + 1;  // reach of the gradient
  for (int x = 0; x < m; ++x) out[x] = 0, out[width - 1 - x] = 0;
  const float *a0 = a_rows[0], *a1 = a_rows[1], *a_mid = a_rows[2], *a3 = a_rows[3], *a4 = a_rows[4];
  const float *b0 = b_rows[0], *b1 = b_rows[1], *b_mid = b_rows[2], *b3 = b_rows[3], *b4 = b_rows[4];
  for (int x = m; x < width - m; ++x) {
    const float gxa = na * (a_mid[x + k] - a_mid[x - k]) + a * (a_mid[x + k + 1] - a_mid[x - k - 1]);
    const float gya = na * (a3[x] - a1[x]) + a * (a4[x] - a0[x]);
    const float gxb = na * (b_mid[x + k] - b_mid[x - k]) + a * (b_mid[x + k + 1] - b_mid[x - k - 1]);
    const float gyb = na * (b3[x] - b1[x]) + a * (b4[x] - b0[x]);
    // Truncation (not lrintf, which the compiler will not vectorise);
    // its bias toward zero is symmetric for both signs.
    out[x] = static_cast<int32_t>((gxa * gya + gxb * gyb) * kGradientFixedPoint);
  }
}

__attribute__((target_clones("avx2", "default"))) void gradientFormRowFrom(
    const float* const a_rows[5], const float* const b_rows[5], int width, double scale, const float* forms,
    int32_t* out) {
  const int k = static_cast<int>(std::floor(scale));
  const float a = static_cast<float>(scale - k), na = 1 - a;
  const int m = k + 1;
  for (int x = 0; x < m; ++x) out[x] = 0, out[width - 1 - x] = 0;
  const float *a0 = a_rows[0], *a1 = a_rows[1], *a_mid = a_rows[2], *a3 = a_rows[3], *a4 = a_rows[4];
  const float *b0 = b_rows[0], *b1 = b_rows[1], *b_mid = b_rows[2], *b3 = b_rows[3], *b4 = b_rows[4];
  // Block by block, the form fixed inside each (a loop the compiler vectorises).
  for (int x0 = m; x0 < width - m;) {
    const float* f = forms + 6 * (x0 / kFormBlock);
    const float fa = f[0], fb = f[1], fc = f[2];
    const int x1 = std::min(width - m, (x0 / kFormBlock + 1) * kFormBlock);
    for (int x = x0; x < x1; ++x) {
      const float gxa = na * (a_mid[x + k] - a_mid[x - k]) + a * (a_mid[x + k + 1] - a_mid[x - k - 1]);
      const float gya = na * (a3[x] - a1[x]) + a * (a4[x] - a0[x]);
      const float gxb = na * (b_mid[x + k] - b_mid[x - k]) + a * (b_mid[x + k + 1] - b_mid[x - k - 1]);
      const float gyb = na * (b3[x] - b1[x]) + a * (b4[x] - b0[x]);
      const float v = fa * (gxa * gxa + gxb * gxb) + fb * (gxa * gya + gxb * gyb) + fc * (gya * gya + gyb * gyb);
      out[x] = static_cast<int32_t>(v * kGradientFixedPoint);
    }
    x0 = x1;
  }
}

void gradientDotRow(const float* ca, const float* cb, int width, int height, double scale, int y, int32_t* out) {
  const int k = static_cast<int>(std::floor(scale));
  const int m = k + 1;
  if (y < m || y >= height - m || width <= 2 * m) {
    std::memset(out, 0, sizeof(int32_t) * width);
    return;
  }
  const size_t w = width;
  const float* a_rows[5] = {ca + (y - k - 1) * w, ca + (y - k) * w, ca + y * w, ca + (y + k) * w,
                            ca + (y + k + 1) * w};
  const float* b_rows[5] = {cb + (y - k - 1) * w, cb + (y - k) * w, cb + y * w, cb + (y + k) * w,
                            cb + (y + k + 1) * w};
  gradientDotRowFrom(a_rows, b_rows, width, scale, out);
}

void gradientDotRows(const float* ca, const float* cb, int width, int height, double scale, int32_t* g,
                     int y_begin, int y_end) {
  for (int y = y_begin; y < y_end; ++y)
    gradientDotRow(ca, cb, width, height, scale, y, g + static_cast<size_t>(y) * width);
}

namespace {

// The gradient energy of the window of radius r around (x, y): the mean of
// term(gxa, gya, gxb, gyb) over its cells, halved; `term` gives a cell's
// energy from its gradients in both chroma channels. Inlined into each
// caller's instruction-set clone.
template <class Term>
__attribute__((always_inline)) inline float windowEnergy(const float* ca, const float* cb, int width, double scale,
                                                         int x, int y, int r, float give_up_above, Term term) {
  const int k = static_cast<int>(std::floor(scale));
  const float a = static_cast<float>(scale - k), na = 1 - a;
  const size_t w = width;
  const int side = 2 * r + 1;
  const double n = static_cast<double>(side) * side;
  // The terms are never negative: once a partial sum is over the limit, so
  // is the whole.
  const double give_up_sum = 2.0 * static_cast<double>(give_up_above) * n;
  double sum = 0;
  // Column strips; in each, per-column float sums down the window (a loop
  // the compiler vectorises across columns), then the columns in double.
  constexpr int kStrip = 64;
  for (int j0 = 0; j0 < side; j0 += kStrip) {
    const int cols = std::min(kStrip, side - j0);
    const int x0 = x - r + j0;
    float acc[kStrip] = {};
    for (int yy = y - r; yy <= y + r; ++yy) {
      const float* am = ca + yy * w + x0;
      const float* bm = cb + yy * w + x0;
      const float *ap = ca + (yy + k) * w + x0, *an = ca + (yy - k) * w + x0;
      const float *ap1 = ca + (yy + k + 1) * w + x0, *an1 = ca + (yy - k - 1) * w + x0;
      const float *bp = cb + (yy + k) * w + x0, *bn = cb + (yy - k) * w + x0;
      const float *bp1 = cb + (yy + k + 1) * w + x0, *bn1 = cb + (yy - k - 1) * w + x0;
      for (int j = 0; j < cols; ++j) {
        const float gxa = na * (am[j + k] - am[j - k]) + a * (am[j + k + 1] - am[j - k - 1]);
        const float gya = na * (ap[j] - an[j]) + a * (ap1[j] - an1[j]);
        const float gxb = na * (bm[j + k] - bm[j - k]) + a * (bm[j + k + 1] - bm[j - k - 1]);
        const float gyb = na * (bp[j] - bn[j]) + a * (bp1[j] - bn1[j]);
        acc[j] += term(gxa, gya, gxb, gyb);
      }
      if (((yy - y + r) & 3) == 3) {  // every fourth row: is it over already?
        double partial = sum;
        for (int j = 0; j < cols; ++j) partial += acc[j];
        if (partial > give_up_sum) return give_up_above;
      }
    }
    for (int j = 0; j < cols; ++j) sum += acc[j];
  }
  return static_cast<float>(0.5 * sum / n);
}

}  // namespace

__attribute__((target_clones("avx2", "default"))) float windowGradientEnergy(const float* ca, const float* cb,
                                                                             int width, double scale, int x, int y,
                                                                             int r, float give_up_above) {
  return windowEnergy(ca, cb, width, scale, x, y, r, give_up_above, [](float gxa, float gya, float gxb, float gyb) {
    return gxa * gxa + gya * gya + gxb * gxb + gyb * gyb;
  });
}

__attribute__((target_clones("avx2", "default"))) float windowGradientEnergyForm(
    const float* ca, const float* cb, int width, double scale, int x, int y, int r, const float q[3],
    float give_up_above) {
  const float qxx = q[0], qxy2 = 2 * q[1], qyy = q[2];
  return windowEnergy(ca, cb, width, scale, x, y, r, give_up_above,
                      [=](float gxa, float gya, float gxb, float gyb) {
                        return qxx * (gxa * gxa + gxb * gxb) + qxy2 * (gxa * gya + gxb * gyb) +
                               qyy * (gya * gya + gyb * gyb);
                      });
}

}  // namespace dv

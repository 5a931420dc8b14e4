#include "detection/color_classes.h"

#include <algorithm>
#include <limits>

namespace dv {
namespace {

int nearestSample(const ColorVec* s, int n, const ColorVec& c, int skip) {
  int best = -1;
  float best_d = std::numeric_limits<float>::max();
  for (int i = 0; i < n; ++i) {
    if (i == skip) continue;
    const float d = colorDistance(s[i], c);
    if (d < best_d) best_d = d, best = i;
  }
  return best;
}

}  // namespace

TwoMeansResult oneClass(const ColorVec* samples, int n, const ColorVec prior[2], int cls, uint8_t* labels) {
  TwoMeansResult r;
  r.mean[0] = prior[0];
  r.mean[1] = prior[1];
  if (n <= 0) return r;
  ColorVec all;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) all.c[k] += samples[i].c[k] / n;
  if (cls < 0) cls = colorDistance(all, prior[0]) <= colorDistance(all, prior[1]) ? 0 : 1;
  for (int i = 0; i < n; ++i) labels[i] = static_cast<uint8_t>(cls);
  r.mean[cls] = all;
  r.count[cls] = n;
  return r;
}

TwoMeansResult twoMeans(const ColorVec* samples, int n, const ColorVec prior[2],
                        const ColorVec* externals, int n_externals, uint8_t* labels) {
  TwoMeansResult r;
  r.mean[0] = prior[0];
  r.mean[1] = prior[1];
  if (n <= 0) return r;

  // The one-cluster answer: the class whose prior is nearest to the mean.
  auto oneCluster = [&]() { return oneClass(samples, n, prior, -1, labels); };
  if (n < 2) return oneCluster();

  // Start each class at the sample nearest to its prior; the class whose
  // prior is closer keeps a shared nearest sample.
  int s0 = nearestSample(samples, n, prior[0], -1);
  int s1 = nearestSample(samples, n, prior[1], -1);
  if (s0 == s1) {
    if (colorDistance(samples[s0], prior[0]) <= colorDistance(samples[s1], prior[1]))
      s1 = nearestSample(samples, n, prior[1], s0);
    else
      s0 = nearestSample(samples, n, prior[0], s1);
  }
  ColorVec m[2] = {samples[s0], samples[s1]};
  for (int i = 0; i < n; ++i) labels[i] = 255;
  for (int iter = 0; iter < 16; ++iter) {
    bool changed = false;
    for (int i = 0; i < n; ++i) {
      const uint8_t l = colorDistance(samples[i], m[0]) <= colorDistance(samples[i], m[1]) ? 0 : 1;
      if (l != labels[i]) labels[i] = l, changed = true;
    }
    if (!changed) break;
    ColorVec sum[2];
    int cnt[2] = {0, 0};
    for (int i = 0; i < n; ++i) {
      ++cnt[labels[i]];
      for (int k = 0; k < 3; ++k) sum[labels[i]].c[k] += samples[i].c[k];
    }
    for (int c = 0; c < 2; ++c)
      if (cnt[c] > 0)
        for (int k = 0; k < 3; ++k) m[c].c[k] = sum[c].c[k] / cnt[c];
  }
  int cnt[2] = {0, 0};
  for (int i = 0; i < n; ++i) ++cnt[labels[i]];
  if (cnt[0] == 0 || cnt[1] == 0) return oneCluster();

  // Separation test (eq. 5.24): d_c >= 0.5 (d_e - d_s).
  float d_s = std::numeric_limits<float>::max();
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) d_s = std::min(d_s, colorDistance(samples[i], samples[j]));
  float d_e = std::numeric_limits<float>::max();
  for (int e = 0; e < n_externals; ++e)
    for (int i = 0; i < n; ++i) d_e = std::min(d_e, colorDistance(samples[i], externals[e]));
  if (n_externals == 0) d_e = 0;
  const float d_c = colorDistance(m[0], m[1]);
  if (d_c < 0.5f * (d_e - d_s)) return oneCluster();
  // Nor are two means within twice the least reach of a class: a split of
  // one class by its noise, which the test above lets pass where an
  // external lies near (a yellow-green marker beside yellow under tungsten
  // light). Green and pink under saturation 0.4 lie four times as far apart.
  if (d_c < 2 * kMinClassRadius) return oneCluster();

  // Keep the class order that fits the priors best.
  const float keep = colorDistance(m[0], prior[0]) + colorDistance(m[1], prior[1]);
  const float swap = colorDistance(m[0], prior[1]) + colorDistance(m[1], prior[0]);
  if (swap < keep) {
    std::swap(m[0], m[1]);
    std::swap(cnt[0], cnt[1]);
    for (int i = 0; i < n; ++i) labels[i] = static_cast<uint8_t>(1 - labels[i]);
  }
  r.mean[0] = m[0];
  r.mean[1] = m[1];
  r.count[0] = cnt[0];
  r.count[1] = cnt[1];
  r.separated = true;
  return r;
}

}  // namespace dv

#include <Eigen/Dense>

namespace dv {

void ColorMap::fit(const ColorVec* reference, const ColorVec* observed, int n) {
  if (n < 3) return;
  // The third chroma channel follows from the first two (their sum is
  // nearly constant), so an affine map of (c0, c1) has 3 unknowns per output.
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d atb = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d a(reference[i].c[0], reference[i].c[1], 1.0);
    const Eigen::Vector3d b(observed[i].c[0], observed[i].c[1], observed[i].c[2]);
    ata += a * a.transpose();
    atb += a * b.transpose();
  }
  Eigen::FullPivLU<Eigen::Matrix3d> lu(ata);
  if (lu.rank() < 3 || std::abs(ata.determinant()) < 1e-3) return;
  const Eigen::Matrix3d x = lu.solve(atb);  // column k: coefficients of output k
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) m_[k][j] = x(j, k);
  valid_ = true;
}

ColorVec ColorMap::apply(const ColorVec& c) const {
  if (!valid_) return c;
  ColorVec r;
  for (int k = 0; k < 3; ++k)
    r.c[k] = static_cast<float>(m_[k][0] * c.c[0] + m_[k][1] * c.c[1] + m_[k][2]);
  return r;
}

void orderByRatio(TwoMeansResult& r, uint8_t* labels, int n, int num, int den, const float* white) {
  auto ratio = [&](const float* c) { return c[num] / std::max(c[den], 1e-3f); };
  bool swap = false;
  if (r.count[0] > 0 && r.count[1] > 0) {
    swap = ratio(r.mean[1].c) < ratio(r.mean[0].c);
  } else if (white && n > 0) {
    const int cls = r.count[0] > 0 ? 0 : 1;
    swap = (ratio(r.mean[cls].c) > ratio(white)) != (cls == 1);
  }
  if (!swap) return;
  std::swap(r.mean[0], r.mean[1]);
  std::swap(r.count[0], r.count[1]);
  for (int i = 0; i < n; ++i) labels[i] = static_cast<uint8_t>(1 - labels[i]);
}

}  // namespace dv

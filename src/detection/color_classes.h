#pragma once
// Position based color classification (thesis §5.3.5): once the position of
// a blob says which two classes it can belong to (yellow/blue for centers,
// green/pink for sides, orange/field for ball candidates), k-means with k = 2
// learns the class colors from the frame itself, and the separation test
// (eq. 5.24) decides whether the samples hold one or two clusters.
//
// Colors are compared as chromaticity scaled to 0..300 (r, g, b divided by
// their sum), so that uneven light, dark exposure and flicker, which scale
// all channels alike, move colors little; white balance shifts remain and
// are what the learning absorbs.
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace dv {

namespace color_class {
// The detector's color classes, in the order of DetectorOptions' references.
enum Id { kYellow = 0, kBlue, kGreen, kPink, kOrange, kField, kWhite, kNumClasses };
}  // namespace color_class

struct ColorVec {
  float c[3] = {0, 0, 0};
};

// Chromaticity feature of an RGB color (0..255 per channel). The small
// constant keeps near-black blobs (noise) from getting extreme chroma.
inline ColorVec colorFeature(float r, float g, float b) {
  const float k = 300.f / (r + g + b + 15.f);
  return {{r * k, g * k, b * k}};
}

inline float colorDistance(const ColorVec& a, const ColorVec& b) {
  const float d0 = a.c[0] - b.c[0], d1 = a.c[1] - b.c[1], d2 = a.c[2] - b.c[2];
  return std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

// Hue angle (rad, (-pi, pi]: 0 red, about +1 yellow, 2.1 green, -2.1 blue,
// -0.6 pink) of an RGB color (or a ColorVec, which is proportional to one)
// seen under white `white`: each channel divided by the white's first, so a
// global cast moves no hue. The order of the hues of two colors also
// survives a camera's saturation and gamma.
inline float colorHue(const float rgb[3], const float white[3]) {
  const float r = rgb[0] / white[0], g = rgb[1] / white[1], b = rgb[2] / white[2];
  return std::atan2(0.8660254f * (g - b), r - 0.5f * (g + b));
}

inline ColorVec colorMix(const ColorVec& a, float wa, const ColorVec& b, float wb,
                         const ColorVec& c, float wc) {
  ColorVec r;
  for (int i = 0; i < 3; ++i) r.c[i] = wa * a.c[i] + wb * b.c[i] + wc * c.c[i];
  return r;
}

// The least distance (chromaticity units) a class reaches from its color:
// a blob's mean color varies by a few, and one or two samples give no spread.
constexpr float kMinClassRadius = 8.f;
// A class reaches kClassSpreads times the spread of its samples in this
// frame (rms distance to its color), at least kMinClassRadius.
constexpr float kClassSpreads = 3.f;
inline float classReach(float spread) { return std::max(kClassSpreads * spread, kMinClassRadius); }

struct TwoMeansResult {
  ColorVec mean[2];     // class colors of this frame (c_c), class order as `prior`
  int count[2] = {0, 0};
  bool separated = false;  // eq. 5.24 found two clusters
};

// k-means with k = 2 over `n` samples, each class started at the sample
// nearest to its prior color (the previous class color). `externals` are
// colors of a definitely different kind (eq. 5.24's external reference).
// Writes the class (0/1, in prior order) of every sample to `labels`. When
// the samples form one cluster, all get the class whose prior is nearest to
// their mean. No allocation.
TwoMeansResult twoMeans(const ColorVec* samples, int n, const ColorVec prior[2],
                        const ColorVec* externals, int n_externals, uint8_t* labels);
// The one-cluster answer: every sample of class `cls` (-1: the class
// whose prior is nearest to their mean), their mean that class's color,
// the other class its prior with no sample.
TwoMeansResult oneClass(const ColorVec* samples, int n, const ColorVec prior[2], int cls, uint8_t* labels);

// Which of twoMeans's two clusters is which class, from an order that no
// global cast, saturation or gamma changes: the ratio of channel `num` to
// channel `den` is the larger in class 1 (blue's blue to green against
// yellow's; pink's red to green against green's). One cluster alone is
// class 1 when its ratio is above that of `white` (the lines' RGB; nullptr
// where unknown: the priors' choice stands). Swaps the means, counts and
// the n `labels` where the priors chose the other way round.
void orderByRatio(TwoMeansResult& r, uint8_t* labels, int n, int num, int den, const float* white);

// One learned class color with retention and reference forces (eq. 5.25).
struct ColorClass {
  ColorVec reference;
  ColorVec color;  // current class color (c_p for the next frame)
  void reset() { color = reference; }
  // c_u = f_p c_p + f_r c_r + (1 - f_p - f_r) c_c
  void update(const ColorVec& frame_color, float f_p, float f_r) {
    color = colorMix(color, f_p, reference, f_r, frame_color, 1.f - f_p - f_r);
  }
};

}  // namespace dv

namespace dv {

// An affine map of chromaticity learned from the classes seen in a frame
// (reference color -> observed class color). It carries how this camera's
// white balance, saturation and exposure move colors over to classes that
// were not seen yet, such as the ball's orange before any ball was found.
class ColorMap {
 public:
  void reset() { valid_ = false; }
  bool valid() const { return valid_; }
  // Least-squares fit from n >= 3 pairs; keeps the previous map when the
  // pairs are degenerate.
  void fit(const ColorVec* reference, const ColorVec* observed, int n);
  ColorVec apply(const ColorVec& c) const;

 private:
  bool valid_ = false;
  double m_[3][3] = {{0}};  // out_k = m_k0 c0 + m_k1 c1 + m_k2
};

}  // namespace dv

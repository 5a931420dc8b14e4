// Which cluster is which class (detection/color_classes.h: orderByRatio),
// under global casts far beyond the presets: the team and marker colors
// the league's teams use, seen through any white balance from tungsten to
// cold LED, a green-magenta tint, saturation 0.4-1.3 and gamma 0.6-1.6.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "detection/color_classes.h"
#include "detection/detector.h"

namespace dv {
namespace {

struct Rgb {
  float v[3];
};

Rgb lerp(const Rgb& a, const Rgb& b, float t) {
  return {{a.v[0] + t * (b.v[0] - a.v[0]), a.v[1] + t * (b.v[1] - a.v[1]), a.v[2] + t * (b.v[2] - a.v[2])}};
}

// A camera's global cast: channel gains, then saturation about the luma,
// then gamma, clipped to 0..255.
struct Cast {
  float gain[3], saturation, gamma;
  Rgb apply(const Rgb& c) const {
    float x[3];
    for (int k = 0; k < 3; ++k) x[k] = c.v[k] * gain[k];
    const float luma = 0.299f * x[0] + 0.587f * x[1] + 0.114f * x[2];
    Rgb out;
    for (int k = 0; k < 3; ++k) {
      const float s = std::clamp(luma + saturation * (x[k] - luma), 0.f, 255.f);
      out.v[k] = 255.f * std::pow(s / 255.f, gamma);
    }
    return out;
  }
};

ColorVec feature(const Rgb& c) { return colorFeature(c.v[0], c.v[1], c.v[2]); }
ColorVec feature(const ColorRef& c) { return colorFeature(c.r, c.g, c.b); }

// The ends of what teams use for each marker color.
const Rgb kLemon{{240, 230, 60}}, kAmber{{245, 160, 20}};
const Rgb kSky{{80, 170, 240}}, kNavy{{20, 40, 130}};
const Rgb kYellowGreen{{150, 220, 50}}, kTeal{{0, 170, 150}};
const Rgb kRose{{250, 180, 200}}, kMagenta{{220, 30, 160}};
const Rgb kWhite{{235, 235, 235}};

Cast randomCast(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.f, 1.f);
  // Tungsten (1.6, 1, 0.6) to cold LED (0.7, 1, 1.7), and a tint.
  const float t = u(rng), tint = 0.85f + 0.3f * u(rng);
  Cast c;
  c.gain[0] = 1.6f + t * (0.7f - 1.6f);
  c.gain[1] = tint;
  c.gain[2] = 0.6f + t * (1.7f - 0.6f);
  c.saturation = 0.4f + 0.9f * u(rng);
  c.gamma = 0.6f + 1.0f * u(rng);
  return c;
}

// Two classes of samples, each of one shade from its range plus a little
// noise, clustered from the shipped references as priors; class 1 must be
// the one whose channel num / den ratio is the larger by nature.
void expectOrdered(const Rgb lo[2], const Rgb hi[2], const ColorRef* prior_ref[2], const ColorRef* ext_ref[2],
                   int num, int den, const char* what) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::normal_distribution<float> noise(0.f, 3.f);
  const ColorVec prior[2] = {feature(*prior_ref[0]), feature(*prior_ref[1])};
  int wrong = 0, wrong_alone = 0;
  const int kCasts = 400;
  for (int i = 0; i < kCasts; ++i) {
    const Cast cast = randomCast(rng);
    const Rgb shade[2] = {lerp(lo[0], hi[0], u(rng)), lerp(lo[1], hi[1], u(rng))};
    std::vector<ColorVec> s;
    std::vector<int> truth;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 4; ++j) {
        Rgb c = shade[k];
        for (float& v : c.v) v = std::clamp(v + noise(rng), 0.f, 255.f);
        s.push_back(feature(cast.apply(c)));
        truth.push_back(k);
      }
    const Rgb white = cast.apply(kWhite);
    // The external colors are the other classes as this frame shows them.
    const ColorVec ext[2] = {feature(cast.apply({{ext_ref[0]->r, ext_ref[0]->g, ext_ref[0]->b}})),
                             feature(cast.apply({{ext_ref[1]->r, ext_ref[1]->g, ext_ref[1]->b}}))};
    std::vector<uint8_t> labels(s.size());
    TwoMeansResult r = twoMeans(s.data(), 8, prior, ext, 2, labels.data());
    orderByRatio(r, labels.data(), 8, num, den, white.v);
    for (int j = 0; j < 8; ++j) wrong += labels[j] != truth[j];
    // Each class alone (one team on the field): placed by the lines' white.
    for (int k = 0; k < 2; ++k) {
      TwoMeansResult one = twoMeans(s.data() + 4 * k, 4, prior, ext, 2, labels.data());
      orderByRatio(one, labels.data(), 4, num, den, white.v);
      for (int j = 0; j < 4; ++j) wrong_alone += labels[j] != k;
    }
  }
  EXPECT_EQ(wrong, 0) << what << ": samples in the wrong class of " << 8 * kCasts;
  EXPECT_EQ(wrong_alone, 0) << what << ", one class alone: samples in the wrong class of " << 8 * kCasts;
}

TEST(ColorOrder, TeamsKeepTheirClassUnderAnyCast) {
  const DetectorOptions d;
  const Rgb lo[2] = {kLemon, kSky}, hi[2] = {kAmber, kNavy};
  const ColorRef* prior[2] = {&d.ref_yellow, &d.ref_blue};
  const ColorRef* ext[2] = {&d.ref_green, &d.ref_pink};
  expectOrdered(lo, hi, prior, ext, 2, 1, "yellow / blue");
}

TEST(ColorOrder, MarkersKeepTheirClassUnderAnyCast) {
  const DetectorOptions d;
  const Rgb lo[2] = {kYellowGreen, kRose}, hi[2] = {kTeal, kMagenta};
  const ColorRef* prior[2] = {&d.ref_green, &d.ref_pink};
  const ColorRef* ext[2] = {&d.ref_yellow, &d.ref_blue};
  expectOrdered(lo, hi, prior, ext, 0, 1, "green / pink");
}

}  // namespace
}  // namespace dv

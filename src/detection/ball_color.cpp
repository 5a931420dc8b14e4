#include "detection/ball_color.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dv {

using namespace color_class;

float streakColorDistance(const ClippedColor& seen, const ColorVec& field, const ColorVec& object,
                          const ColorVec* white) {
  float best = std::numeric_limits<float>::max();
  const int chroma_steps = white ? kStreakShareSteps : 1;
  for (int i = 0; i < kStreakShareSteps; ++i) {
    const float a = kStreakMinShare + (1.f - kStreakMinShare) * i / (kStreakShareSteps - 1);
    const ColorVec mix = colorMix(field, 1.f - a, object, a, object, 0.f);
    for (int j = 0; j < chroma_steps; ++j) {
      const float s = 1.f - (1.f - kStreakMinChroma) * j / std::max(1, kStreakShareSteps - 1);
      best = std::min(best, seen.distance(j == 0 ? mix : colorMix(mix, s, *white, 1.f - s, mix, 0.f)));
    }
  }
  return best;
}

BallColorJudge::BallColorJudge(const FrameColors& frame, float min_brightness, bool fade_streaks)
    : f_(frame), min_brightness_(min_brightness), fade_streaks_(fade_streaks) {
  if (f_.white.valid)
    for (int k = 0; k < 3; ++k) white_[k] = f_.white.rgb[k];
}

float BallColorJudge::saturation(const float rgb[3]) const {
  const float r = rgb[0] / white_[0], g = rgb[1] / white_[1], b = rgb[2] / white_[2];
  const float hi = std::max({r, g, b}), lo = std::min({r, g, b});
  return hi > 0 ? (hi - lo) / hi : 0.f;
}

float BallColorJudge::explainedByNone(const float rgb[3]) const { return explainedByNone(ClippedColor(rgb)); }

float BallColorJudge::explainedByNone(const ClippedColor& seen) const {
  const float* rgb = seen.rgb();
  if (!f_.seen[kYellow] || rgb[0] + rgb[1] + rgb[2] < min_brightness_) return 0;
  if (saturation(rgb) < kBallSaturationShare * saturation(f_.color[kYellow].c)) return 0;
  const HueSpan hs = hueSpan(seen);
  if (!(hs.hue > hs.pink && hs.hue < hs.yellow)) return 0;
  const bool redder_than_yellow = f_.white.valid && hs.hue < f_.yellow_hue_min - hs.noise;
  float rel = std::numeric_limits<float>::max();
  for (int k : {kYellow, kPink, kWhite, kField}) {
    if (k == kYellow && redder_than_yellow) continue;
    const float radius = classReach(f_.spread[k]);
    rel = std::min(rel, seen.distance(f_.color[k]) / radius);
  }
  return rel;
}

BallColorJudge::HueSpan BallColorJudge::hueSpan(const ClippedColor& seen) const {
  HueSpan hs;
  hs.hue = colorHue(seen.rgb(), white_);
  hs.yellow = colorHue(f_.color[kYellow].c, white_);
  hs.pink = std::min(0.f, colorHue(f_.color[kPink].c, white_));
  hs.noise = std::atan2(kMinClassRadius, seen.distance(f_.color[kWhite]));
  return hs;
}

bool BallColorJudge::hueClearlyBetweenPinkAndYellow(const ClippedColor& seen) const {
  const HueSpan hs = hueSpan(seen);
  return hs.hue > hs.pink + hs.noise && hs.hue < hs.yellow - hs.noise;
}

const ColorVec* BallColorJudge::streakWhite(const ClippedColor& seen) const {
  const float* rgb = seen.rgb();
  if (!fade_streaks_ || !f_.white.valid || rgb[0] + rgb[1] + rgb[2] < min_brightness_) return nullptr;
  return &f_.color[kWhite];
}

float BallColorJudge::distanceToOrange(const ClippedColor& seen, bool streak) const {
  auto classDistance = [&](const ColorVec& c) {
    return streak ? streakColorDistance(seen, f_.color[kField], c, streakWhite(seen)) : seen.distance(c);
  };
  float d = classDistance(f_.color[kOrange]);
  if (f_.mapped_orange) d = std::min(d, classDistance(*f_.mapped_orange));
  return d;
}

double BallColorJudge::confidence(const float rgb[3], bool streak, int* nearest) const {
  return confidence(ClippedColor(rgb), streak, nearest);
}

double BallColorJudge::confidence(const ClippedColor& seen, bool streak, int* nearest, bool* unexpected) const {
  if (seen.saturated()) return 0;
  const float d_or = distanceToOrange(seen, streak);
  float d_neg = std::numeric_limits<float>::max();
  int nearest_neg = kField;
  for (int k : {kField, kWhite, kPink, kGreen, kYellow, kBlue}) {
    const float dk = k == kField || !streak
                         ? seen.distance(f_.color[k])
                         : streakColorDistance(seen, f_.color[kField], f_.color[k], streakWhite(seen));
    if (dk < d_neg) d_neg = dk, nearest_neg = k;
  }
  if (nearest) *nearest = nearest_neg;
  const float unexplained = streak ? 0.f : explainedByNone(seen);
  if (d_or >= d_neg && unexplained <= 1) return 0;
  if (unexpected) *unexpected = d_or >= d_neg;
  const double margin_ratio = (d_neg - d_or) / (d_neg + d_or);
  return std::max(std::min(1.0, margin_ratio / 0.3), std::min(1.0, static_cast<double>(unexplained) - 1));
}

bool BallColorJudge::withinFieldReach(const ClippedColor& seen) const {
  const float reach = classReach(f_.spread[kField]);
  return seen.distance(f_.color[kField]) <= reach;
}

bool BallColorJudge::isBall(const float rgb[3]) const {
  const ClippedColor seen(rgb);
  if (seen.saturated()) return false;
  if (withinFieldReach(seen) && seen.distance(f_.color[kField]) <= distanceToOrange(seen, false)) return false;
  return confidence(seen, false, nullptr) > 0;
}

bool BallColorJudge::isCarpet(const float rgb[3]) const {
  const ClippedColor seen(rgb);
  return !seen.saturated() && withinFieldReach(seen);
}

}  // namespace dv

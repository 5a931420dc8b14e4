#pragma once
// Whether a color is the ball's in one frame, and how clearly: for blobs,
// streaks and the border's samples alike. No color is fixed: the ball is
// what is nearer to the orange class than to every other class this frame
// learned (a clipped channel counts as the color it may have had: an
// overexposed ball looks yellowish), or what none of this frame's classes
// explains (a ball of another shade than expected: explainedByNone). A
// streak is the ball's color mixed with the carpet it crossed: it is
// compared with each class's mixing line from the field color.
#include <optional>

#include "detection/border_balls.h"
#include "detection/clipped_color.h"
#include "detection/color_classes.h"
#include "pipeline/blob.h"

namespace dv {
// A ball of an unexpected shade is at least this share as saturated as the
// frame's yellow, both under the lines' white (line and carpet mixes are
// far less).
constexpr float kBallSaturationShare = 0.5f;

// One frame's colors as the detector learned them (chromaticity,
// color_classes.h).
struct FrameColors {
  ColorVec color[color_class::kNumClasses];
  float spread[color_class::kNumClasses] = {};  // rms distance of its samples (0: unknown)
  bool seen[color_class::kNumClasses] = {};     // the class had samples in this frame
  NeutralColor white;                           // the lines' RGB (pipeline/blob.h)
  // Hue (colorHue under `white`) of the reddest unclipped yellow center.
  float yellow_hue_min = 0;
  // The orange reference as this camera shows colors (ColorMap), if known.
  std::optional<ColorVec> mapped_orange;
};

class BallColorJudge final : public BallColorTest {
 public:
  // min_brightness: r + g + b below which no class-less color is a ball
  // (darker peaks lie on robot tops). fade_streaks: a streak's chroma may
  // have faded (kStreakMinChroma); not where a color near the lines' mix
  // with the carpet lies on a marking: there a faded ball looks like it.
  BallColorJudge(const FrameColors& frame, float min_brightness, bool fade_streaks = true);

  // The color's confidence, 0..1; 0: not the ball's. `nearest`: the
  // nearest of the other classes; `unexpected`: the confidence is only that
  // no class explains the color (it is not nearer to orange than to them).
  double confidence(const float rgb[3], bool streak, int* nearest = nullptr) const;
  double confidence(const ClippedColor& seen, bool streak, int* nearest = nullptr,
                    bool* unexpected = nullptr) const;
  // As confidence() > 0, with the carpet (most of what the border's probes
  // see) ruled out first: a color nearer to the field than to orange and
  // within the field class's reach is neither nearer to orange nor
  // unexplained.
  bool isBall(const float rgb[3]) const override;
  bool isCarpet(const float rgb[3]) const override;

  // 0 unless yellow was seen, the color is at least min_brightness bright,
  // at least kBallSaturationShare as saturated as the yellow class and its
  // hue lies between this frame's pink and yellow (through red); else its
  // distance to the nearest of the yellow, pink, white and field classes in
  // units of that class's reach (above 1: none explains it). Yellow does
  // not explain a color redder than its reddest center by more than the
  // hue a color's noise (kMinClassRadius) spans at its distance from the
  // white: clipping and vignetting spread the yellow centers along a
  // curve, so a reach around their mean would also cover the redder ball.
  float explainedByNone(const float rgb[3]) const;
  // Whether a color's hue lies between this frame's pink and yellow by more
  // than the hue a color's noise spans at its distance from the white. A
  // blob's mean color must, to be a ball of a shade of its own: a pale
  // yellow (a thin line's demosaiced edge under tungsten, (204, 204, 110))
  // is no more than a paler yellow (the detector still takes such a blob
  // where it stands alone on the carpet, off the markings). Single samples
  // on a ball's rim are judged without it: mixed with the carpet, their hue
  // passes yellow's on the way to green.
  bool hueClearlyBetweenPinkAndYellow(const ClippedColor& seen) const;

 private:
  float explainedByNone(const ClippedColor& seen) const;
  // A color's hue with this frame's pink and yellow hues (pink at most 0,
  // red) and the hue its noise (kMinClassRadius) spans at its distance
  // from the white, all under the lines' white.
  struct HueSpan {
    float hue, pink, yellow, noise;
  };
  HueSpan hueSpan(const ClippedColor& seen) const;
  float distanceToOrange(const ClippedColor& seen, bool streak) const;
  bool withinFieldReach(const ClippedColor& seen) const;
  float saturation(const float rgb[3]) const;  // under the lines' white
  // The white a streak's chroma fades to (streakColorDistance), if the lines
  // gave one and the streak is as bright as a ball may be (min_brightness:
  // a stream keeps the ball's brightness; a shadow's chromaticity says
  // little, and faded it read as a ball's under a green cast).
  const ColorVec* streakWhite(const ClippedColor& seen) const;

  const FrameColors& f_;
  float min_brightness_;
  bool fade_streaks_;
  float white_[3] = {1, 1, 1};
};

// Share of the object's color in a streak's mean color (chromaticity
// weight, which favours the brighter ball over the carpet): a streak's color
// disc lies where the ball covered the cells for at least half the exposure.
constexpr float kStreakMinShare = 0.5f;
constexpr int kStreakShareSteps = 6;

// A streak's chroma may also have faded toward the frame's white by up to
// this share kept: a compressed stream codes color at half resolution and
// coarsest where the picture moves, so a fast ball covering half a chroma
// sample keeps half its chroma (its brightness stays its own).
constexpr float kStreakMinChroma = 0.5f;

// Distance from a streak's color to the mix of `field` and `object` with the
// object's share between kStreakMinShare and 1; with `white`, that mix's
// chroma kept between kStreakMinChroma and all of it.
float streakColorDistance(const ClippedColor& seen, const ColorVec& field, const ColorVec& object,
                          const ColorVec* white = nullptr);

}  // namespace dv

#pragma once
// A ball whose color this frame's classes take for a marker's. Under a
// strong light (a sun patch over tungsten) the ball clips in red to the
// very color of the yellow centers that clip outside it, (255, 209, 30)
// against (255, 210, 24); a pale orange may likewise lie within pink's
// reach. Color alone cannot tell them apart, but where they lie can: a
// center or side dot sits on a robot's top, the ball on the carpet. So a
// round blob of a marker's color, outside every robot, standing alone on
// the carpet, is the ball where the frame shows no ball of the ball's own
// colors. Its silhouette is judged by that marker's class as well as the
// ball's own colors (its shaded side, unclipped, is orange), so it is
// centered like any ball. Nearest to another class (a pale yellow nearer
// to the lines' white or to yellow-green dots), off the markings, its color
// must lie on the ball's own clip path mixed with the carpet around it.
#include "detection/ball_color.h"
#include "detection/seen_color.h"
#include "geometry/robot_pattern.h"

namespace dv {

// Where the ring around a ball that must show carpet lies (mm from its
// center): midway between a center dot's rim and its side dots' inner
// rims, where a robot's top would show (carpetAroundBall).
inline constexpr double kCarpetRingMm = (RobotPatternGeometry::kCenterBlobRadius +
                                         RobotPatternGeometry::kSideBlobDistance -
                                         RobotPatternGeometry::kSideBlobRadius) /
                                        2;

// Ball-colored: as the frame's judge says, or within the reach of one
// marker class of this frame (`marker_class`; -1: none, only the ball's own
// colors as the light clips them count, for the rim) and nearer to it than
// to the carpet: the field class's and, where given, `around`'s (the
// ring's color, colorAroundBall). The sun patch that clips the ball lights
// the carpet too: under a warm cast at saturation 0.43 the lit carpet
// beside a ball, (157, 185, 144), lay within the pale yellow centers' reach
// and nearer to them than to the field class, and it merged with the ball.
// Carpet: as the judge says.
class MarkerColoredBallTest final : public BallColorTest {
 public:
  MarkerColoredBallTest(const FrameColors& frame, const BallColorTest& judge, int marker_class,
                        const ColorVec* around = nullptr)
      : f_(frame), judge_(judge), k_(marker_class), around_(around) {}
  bool isBall(const float rgb[3]) const override;
  // A ball's color mixed with the carpet around it (an over-exposed ball's
  // unclipped rim, unclippedDiscColor, or a blob's mean): the marker's
  // color, or the ball's own as more light clips it, within the class's
  // reach. That carpet is the field class's color or `around`: under a
  // neutral camera at 2.5 times the light the lit carpet's chromaticity
  // moved off the field class's (a rim of (219, 210, 59) lay 14 from
  // yellow, beyond its reach, and off the mix with the field class).
  bool isRim(const float rgb[3]) const;
  bool isCarpet(const float rgb[3]) const override { return judge_.isCarpet(rgb); }

 private:
  const FrameColors& f_;
  const BallColorTest& judge_;
  int k_;
  const ColorVec* around_;
};

// The share (0..1) of a ring around a ball at `center` (image px, radius
// `radius_px`, `ball_radius_mm` on the field, brightness r + g + b
// `brightness`) that shows carpet: the ring lies where, around a center
// dot, the robot's top shows between it and its side dots (35 mm out, a
// ball radius and a half). A sample is carpet where the field is its
// nearest class of the frame but green (not within the field's reach: a
// sun patch lights the carpet around such a ball, and under gamma more
// light moves its chromaticity toward green's, 15 apart under tungsten;
// green dots lie beyond the ring) and it is no darker than a robot's top
// may be beside its markers (kTopBrightness); or, whatever its class and
// darkness, where it lies within a color's noise of the carpet beyond a
// robot's reach around the ball (a ring 105 mm out, its median color,
// where at least half of that ring shows it). Samples beyond the image
// count as no carpet.
// A ball judged by where it lies stands mostly on the carpet: at least half
// of that ring (a ball beside a robot still shows half of it).
// colors null: any color counts, only a robot's top does not (where the
// frame's classes cannot tell the carpet: under a cold cast in H.264 the
// carpet beside a washed-out ball lay nearer to the pale yellow centers
// than to the field class).
// may_be_top: how many samples may show a robot's top (too dark for carpet
// and unlike the carpet beyond, or beyond the image).
inline constexpr double kMinCarpetAroundBall = 0.5;
double carpetAroundBall(const FrameView& frame, const FrameColors* colors, ImagePx center, double radius_px,
                        double ball_radius_mm, float brightness, int* may_be_top = nullptr);
// The share (0..1) of that ring within a color's noise of the carpet beyond
// a robot's reach around `center` (0 where that carpet is not one color):
// around a ball alone, the ring is the carpet it lies on; around a robot's
// center, its top.
double ringLikeTheCarpetBeyond(const FrameView& frame, ImagePx center, double radius_px, double ball_radius_mm);
// What lies around a ball on the same ring: the chromaticity of its
// per-channel median. Around a ball alone that is the carpet (a fast
// ball's streak covers less than half the ring). False where less than
// half the ring lies in the image.
bool colorAroundBall(const FrameView& frame, ImagePx center, double radius_px, double ball_radius_mm, ColorVec& color);
// The same ring's per-channel median RGB.
bool rgbAroundBall(const FrameView& frame, ImagePx center, double radius_px, double ball_radius_mm, float rgb[3]);

}  // namespace dv

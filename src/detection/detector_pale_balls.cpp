// A ball clipped pale: under a sun patch in a bright or desaturated camera
// the ball clips in two or three channels, to a pale yellow or white that
// after the lines' white balance is as little saturated as a line
// crossing, so the pixel stage's color gate drops its peak (BlobList::
// pale). The sweep's tungsten_bright_sun_amber_light_ball clipped it to
// (255, 254, 143); extreme #1091 (a sun patch of 1.87 at exposure 1.3 and
// saturation 0.43) to (245, 250, 225). No hue is left to judge, but its
// shape and place are the ball's: one whole ball's disc standing out from
// the carpet, nothing like it beyond its rim (a clipped carpet or line
// runs on), off the markings and the goals' walls, outside every robot,
// the ring around it the carpet beyond (no robot's top, however lit), and
// its color unlike that ring's (a lit carpet's texture is the carpet's own
// color).
#include "detection/ball_silhouette.h"
#include "detection/detector_impl.h"
#include "detection/marker_colored_ball.h"

namespace dv {

namespace {

// A sample is the ball's where it stands out from the carpet (the ring's
// median, RGB) by more than half as much as the pale blob's mean does: on
// the mix of the two that is a blurred disc's edge, whatever the blur and
// the level either clipped at (a small ball's blurred rim falls below any
// fixed clip level: at 1224 x 1024 the clipped samples covered a third of
// its disc), and the ball's shaded side, darker and more orange than its
// clipped cap, counts as well (taken as carpet, it moved the center 2.8 mm
// toward the light at 2448 x 2048).
class PaleBallTest final : public BallColorTest {
 public:
  PaleBallTest(const float ball[3], const float carpet[3]) {
    for (int k = 0; k < 3; ++k) carpet_[k] = carpet[k];
    half2_ = 0.25f * d2(ball, carpet);
  }
  bool isBall(const float rgb[3]) const override { return d2(rgb, carpet_) > half2_; }
  bool isCarpet(const float rgb[3]) const override { return !isBall(rgb); }

 private:
  static float d2(const float a[3], const float b[3]) {
    float s = 0;
    for (int k = 0; k < 3; ++k) s += (a[k] - b[k]) * (a[k] - b[k]);
    return s;
  }
  float carpet_[3], half2_;
};

}  // namespace

void Detector::Impl::addPaleBalls(double strength_ref, bool tracking) {
  if (!frame_view.image) return;
  int best = -1;
  for (const Blob& b : pale) {
    FieldMm at_ball, at_team[2];
    if (!alongRay(b.position, plane_height, opt.ball_radius, at_ball) ||
        !alongRay(b.position, plane_height, opt.robot_height_yellow, at_team[0]) ||
        !alongRay(b.position, plane_height, opt.robot_height_blue, at_team[1]))
      continue;
    if (!inBallArea(at_ball) || onMarking(at_ball) || onGoalWall(at_ball) || insideAnyRobot(at_ball, at_team))
      continue;
    const auto seen = camera.fieldToImage({b.position.x, b.position.y, plane_height});
    if (!seen) continue;
    const double r = ballRadiusPx(camera, {at_ball.x, at_ball.y, opt.ball_radius}, opt.ball_radius);
    float ring[3];
    if (!rgbAroundBall(frame_view, *seen, r, opt.ball_radius, ring)) continue;
    // Its chromaticity as seen, not as ClippedColor bounds it: two clipped
    // channels free to grow reach a lit carpet clipped in green (the
    // condition's ring, about (143, 222, 87)). A lit carpet's texture peak
    // is the carpet's own color.
    if (colorDistance(colorFeature(b.rgb[0], b.rgb[1], b.rgb[2]), colorFeature(ring[0], ring[1], ring[2])) <=
        kMinClassRadius)
      continue;
    const PaleBallTest test(b.rgb, ring);
    ImagePx center;
    if (!ballSilhouetteCenter(frame_view, test, *seen, r, center)) continue;
    // No robot's top around it, however lit (extreme #1210: a yellow
    // robot's white-clipped center on a brown top at gamma 0.63 was as
    // bright as a third of its center, the darkness carpetAroundBall
    // allows a ring). That ring, not the peaks around it, tells a robot's
    // dot: a lit carpet's texture peaks anywhere (one 65 mm from the
    // condition's ball at 1224 x 1024), and the ball's own streak peak
    // lies beside its round one.
    const double carpet = ringLikeTheCarpetBeyond(frame_view, center, r, opt.ball_radius);
    if (carpet < kMinCarpetAroundBall) continue;
    const auto on_plane = camera.imageToField(center, opt.ball_radius);
    BallCandidate c;
    c.pos = on_plane ? FieldMm{on_plane->x, on_plane->y} : at_ball;
    keepSurest(c, carpet, b.score, strength_ref, tracking, best);
  }
}

}  // namespace dv

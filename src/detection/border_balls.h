#pragma once
// A ball at the image border: cut by it, or whole but so near it that the
// pixel stage's blob score cannot see it. That score needs a side blob's
// whole disc and its surround in view (score_windows.h: cells beyond the
// image repeat the border samples, whose gradient is zero, so the quadrants
// outside score nothing), so a ball with half of it in the image never
// peaks in any backend or search, and a whole ball within about three of
// its radii of the edge peaks in some searches and not in others (the
// coarse search's windows are twice as wide). It is looked for here, in
// the frame itself along the image border, so every backend and search
// gets the same answer:
//  - probes: image points in rows half a ball radius, then 1.5, 2.5 and
//    3.5 radii inside each edge, 0.8 ball radii apart along it, where a
//    ball there would lie within the walls (made once per camera);
//  - where a probe's color passes the caller's ball test, a window on the
//    edge around the run of such probes (one row) is sampled on a fine
//    lattice and each sample judged by the same test;
//  - the ball's image is a disc of known radius (the ball's radius as the
//    camera sees it there). Cut by the edge: its center along the edge is
//    the centroid of the ball-colored samples, its depth follows from their
//    area (a circular segment's area). Whole: its center is their
//    centroid. No threshold of the fit is tuned to a scene;
//  - the fit must explain the samples (their overlap with the fitted disc
//    or segment, intersection over union, at least kMinBorderOverlap) and
//    a cut ball not be longer than a ball along the edge, so a colored
//    edge, a line or a marker's rim is no ball.
// The detector takes a whole ball from here only where no blob is one.
// No allocation per frame after the first.
#include <cstdint>
#include <vector>

#include "core/units.h"
#include "detection/seen_color.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"

namespace dv {

// Intersection over union of the ball-colored samples and the fitted
// segment: a disc cut by a line, blurred by a few pixels, gives 0.8..0.95.
inline constexpr double kMinBorderOverlap = 0.6;
// Least share of the ball's disc in the image for a fit: the bar is half,
// with room for the fit's error.
inline constexpr double kMinBorderVisible = 0.4;

// Whether a color (0..255 RGB) is the ball's, as the detector judges a blob;
// and whether it is the carpet's (the field class's), which the ball is
// seen against.
class BallColorTest {
 public:
  virtual ~BallColorTest() = default;
  virtual bool isBall(const float rgb[3]) const = 0;
  virtual bool isCarpet(const float rgb[3]) const = 0;
};

struct BorderBall {
  ImagePx center;       // the ball's center in the image (may lie just outside)
  FieldPoint position;  // the ball's center, z = ball radius
  float rgb[3] = {0, 0, 0};  // mean color of its ball-colored samples
  double overlap = 0;   // of the samples and the fitted segment
  double visible = 0;   // share of the disc inside the image
  bool whole = false;   // the whole disc is in the image
};

class BorderBallFinder {
 public:
  BorderBallFinder(const CameraModel& camera, const FieldRect& ball_area, double ball_radius);

  // The balls at the image border in `frame`, appended to `out`.
  void find(const FrameView& frame, const BallColorTest& test, std::vector<BorderBall>& out);

  int probes() const { return static_cast<int>(probes_.size()); }
  double ballRadius() const { return ball_radius_; }

 private:
  struct Probe {
    int edge = 0;     // 0 left, 1 right, 2 top, 3 bottom
    double t = 0;     // px along the edge
    double radius = 0;  // the ball's radius in px there
    int row = 0;      // the sample point lies kProbeInset + row radii inside
    ImagePx at;
  };
  // Image point at `t` along edge `e`, `s` px inside the image.
  ImagePx edgePoint(int edge, double t, double s) const;
  double edgeLength(int edge) const;
  // Fits one run of probes [first, last] (same edge and row); true with a
  // ball.
  bool fit(const FrameView& frame, const BallColorTest& test, int first, int last, BorderBall& ball);

  CameraModel camera_;
  double ball_radius_;
  double width_, height_;
  std::vector<Probe> probes_;
  std::vector<uint8_t> hit_;
  struct Sample {
    double t, s;
    float rgb[3];
  };
  std::vector<Sample> samples_;  // ball-colored samples of one window
};

// The ball's radius in image px at field point p (its center): the mean
// distance from p's image to the images of p moved by the radius across
// the viewing ray (a sphere's outline, not a disc on the field). 0 where p
// is not seen.
double ballRadiusPx(const CameraModel& camera, const FieldPoint& p, double radius);

}  // namespace dv

#pragma once
// Blobs that no color rule takes, linked across frames. A fast ball's
// color can wash out so far that every class explains it better than the
// ball's (tungsten at saturation 0.4 and gamma 0.6 in H.264: the kicked
// ball read (198, 166, 154), nearer to the pale pink dots than to orange,
// in every frame). Its motion still tells it: nothing but a ball moves
// faster than any robot, and a ball keeps its line and its pace. So such a
// blob that continues two earlier ones on a straight course at one pace,
// faster than any robot, is the ball, as sure as it lies where the two put
// it. Fixed capacity: no allocation per frame.
#include <array>

#include "core/units.h"

namespace dv {

class FastStreaks {
 public:
  // Blobs kept per frame (more are clutter: the rest are dropped), and the
  // frames before the current one that a chain may span (a compressed
  // stream can lose the ball for a frame).
  static constexpr int kMaxPerFrame = 16;
  static constexpr int kFramesBefore = 3;

  void setLimits(double max_robot_speed, double max_ball_speed, double ball_radius) {
    max_robot_speed_ = max_robot_speed;
    max_ball_speed_ = max_ball_speed;
    ball_radius_ = ball_radius;
  }
  void clear() { frames_ = {}; }

  // Starts frame t.
  void begin(double t);
  // A blob of frame t that no color rule took (outside every robot, off
  // the markings).
  void add(FieldMm p);
  // 0..1 for such a blob at p in frame t: over the pairs of blobs of two
  // earlier frames whose steps lie between a robot's reach and a ball's
  // (mm/s, setLimits) and that put p's place within two ball radii of it
  // (a ball keeps its line, off it by no more than its blurred picture),
  // 1 - (p's distance from that place) / (its step from the later blob of
  // the pair). 0 where a blob of the frame before lies within a robot's
  // reach of p: a slow thing's (the dots of a robot not found show no
  // ball's color frame after frame); nor may a pair's later blob have such
  // a one.
  double confidence(FieldMm p) const;

 private:
  struct Frame {
    double t = 0;
    int n = 0;
    std::array<FieldMm, kMaxPerFrame> at;
  };
  // Whether frame k holds a blob within a robot's reach of p, at time t.
  bool slowNear(int k, FieldMm p, double t) const;
  std::array<Frame, kFramesBefore + 1> frames_;  // the last is the current frame
  double max_robot_speed_ = 4000, max_ball_speed_ = 6500;  // mm/s
  double ball_radius_ = 21.5;                              // mm
};

}  // namespace dv

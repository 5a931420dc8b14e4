#pragma once
// A robot's orientation read from the frame along the ring its side dots
// lie on (65 mm from the center): the dots are the ring's bright arcs
// beside the dark top, whatever their color. For robots whose dots made
// no peak (pale dots whose chroma is gone), and to tell apart the two
// placements a diagonal pair of side blobs fits.
#include <optional>

#include "core/units.h"
#include "detection/seen_color.h"
#include "geometry/camera_model.h"

namespace dv {

// Points read along the ring (5 degrees apart).
inline constexpr int kRingPoints = 72;
// A robot's dots are at least this many times as bright as its top between
// them (4.9 or more on the sweeps' robots; bare carpet's texture 1.3, 3.1
// where a line crosses it).
inline constexpr float kDotOverTop = 2.f;

// The orientation (rad) that puts all four side slots of a robot centered
// at `center` (on the plane z = center.z) on bright ring points, where
// those orientations form one run no wider than a quarter turn; refined
// from where the bright arcs lie. A point is bright nearer to the ring's
// brightest than to its darkest, and at least `min_bright` (r + g + b).
// None where the ring leaves the image, or no single run fits.
std::optional<double> ringOrientation(const FrameView& frame, const CameraModel& camera, const FieldPoint& center,
                                      float min_bright);

// The darkest brightness (r + g + b) along that ring: the robot's top
// between its dots. None where the ring leaves the image.
std::optional<float> ringDarkest(const FrameView& frame, const CameraModel& camera, const FieldPoint& center);

}  // namespace dv

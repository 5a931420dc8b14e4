#pragma once
// Weak peaks as side blobs (hysteresis on blobs, as Canny does for edges):
// the pixel stage hands over peaks that score just below the blob threshold
// (BlobList::weak). Alone they are mostly carpet texture and noise, so the
// detector takes one only where a robot pattern made of blobs predicts a
// side blob: the center blob and at least two side blobs fix the pose, and
// each weak peak must lie within a few millimetres of the slot the pose puts
// it in. A weak peak is never a center, never a ball, never part of the
// frame's color classes, and its color decides a side's marker only when it
// is clearly nearer to one of the two side colors.
#include "detection/blob_index.h"
#include "detection/color_classes.h"
#include "detection/pattern_fit.h"
#include "geometry/robot_pattern.h"

namespace dv {

// For each slot s (0..4) whose bit is clear in `filled`, the weak peak of
// `weak` nearest to where `pose` puts the slot, if closer than `tolerance`
// (its mm, stretched along the viewing ray: the along-ray part of a
// distance is divided by the stretch; pattern_fit.h) (index into
// weak.points(), else -1), and that distance. Returns how many slots were
// found.
int findWeakSlots(const PatternPose& pose, unsigned filled, BlobIndex& weak, const FitTolerance& tolerance,
                  int found[kPatternSlots], double error[kPatternSlots]);

// The side marker a weak peak's color shows: 0 (like `green`), 1 (like
// `pink`), or -1 when it is not clearly nearer to one of them: its distance
// to the nearer must stay below `margin` times its distance to the other.
int weakSideColor(const ColorVec& color, const ColorVec& green, const ColorVec& pink, float margin);

// As weakSideColor for a dot of `color` seen as `rgb` (0..255): where one
// channel is at the clip level it is free to grow (clipped_color.h: a pink
// dot clipped in red is redder than it shows). `nearer` gets the nearer of
// the two either way: where the dot is clearly nearer to neither, it is
// still a better guess than a fixed one.
int sideColorOfDot(const ColorVec& color, const float rgb[3], const ColorVec& green, const ColorVec& pink,
                   float margin, MarkerColor& nearer);

}  // namespace dv

#pragma once
// The ball's center in the image from its silhouette. The blob stage puts a
// ball where its score peaks on the sampling grid: on the lit cap, which is
// not the center when the light or the camera comes from the side, and only
// to a grid cell, which from the touch line spans tens of millimetres of
// field. A sphere's image is (to far below a pixel at these sizes) a disc
// around its center's image, and its outline does not depend on shading:
// so the center is the centroid of the ball-colored samples on a lattice of
// a quarter of the ball's image radius (a fraction of a pixel far away),
// judged once around the blob, the centroid's window recentred until it
// settles; then each sample weighed by its share of ball (where its
// chromaticity lies between the ball's and the carpet's), so that the blur
// of a shaded rim counts as that of a lit one. The judge of "ball-colored" is the detector's own (the border
// balls' test), so nothing is tuned to a scene's colors. A silhouette that
// is too small for a whole ball in view (cut, occluded by a robot) or too
// large for one (something orange beside it) leaves the blob's place.
// No allocation.
#include "core/units.h"
#include "detection/border_balls.h"
#include "detection/seen_color.h"

namespace dv {

// The silhouette's center near `start` for a ball of `radius_px` there;
// false where the silhouette does not look like one whole ball.
bool ballSilhouetteCenter(const FrameView& frame, const BallColorTest& test, ImagePx start, double radius_px,
                          ImagePx& center);

// Whether ball-colored samples near `start` cover more than a tenth of one
// ball's disc beyond its rim (1.25 radii around their centroid; a ball
// alone shows none): a ball merged with something of its color, or a
// color along lines rather than on a disc. False where the lattice leaves
// the image.
bool ballColorBeyondRim(const FrameView& frame, const BallColorTest& test, ImagePx start, double radius_px);

}  // namespace dv

#pragma once
// The painted lines look the same after a half turn of the field about its
// centre, so every pose that fits them has a twin that fits them as well,
// looking at the opposite part of the field. Which one is right needs
// knowledge from outside the image (the camera-id layout, a hint, the given
// points); it is decided here and said out loud, never silently.
#include <string>
#include <vector>

#include "core/units.h"
#include "geometry/calibration/camera_params.h"
#include "geometry/field_model.h"

namespace dv {

struct SymmetryDecision {
  // How it was settled: "the camera-id layout (...)", "--region x>0",
  // "--near 2000,0", "the given points".
  std::string basis;
  bool decided = true;
  std::string reason;  // why not, when !decided
  bool by_points = false;
  FieldPoint position{0, 0, 0}, alternative_position{0, 0, 0};  // camera centers
  FieldMm view{0, 0}, alternative_view{0, 0};  // field points at the image center
  // One line for the operator: the choice, its basis and the alternative.
  std::string describe() const;
};

// The same camera after a half turn of the field about its center.
CameraParams halfTurnTwin(const CameraParams& p);

// Where the image center's ray meets the field (z = 0); the point under the
// camera for a view at or above the horizon.
FieldMm viewCenter(const CameraParams& p, int width, int height);

// `found` or its twin, whichever looks nearer to `target`. Undecided when
// the two look at nearly the same place or `target` is about as near to
// both; `params` is `found` then.
struct SymmetryChoice {
  CameraParams params;
  SymmetryDecision decision;
};
SymmetryChoice chooseNearTarget(const CameraParams& found, FieldMm target, const std::string& basis, int width,
                                int height);

// Of the readings (each with its twin), the one that looks into `region`
// (the camera-id layout's region or --region): the region is where the
// image center lands, so the reading whose view center lies in it is taken,
// however near the readings are (a camera aimed at the centre circle). Two
// inside: of a single reading and its twin, the one nearer the region's
// center, undecided when about as near; none inside, or several readings
// inside: undecided.
SymmetryChoice chooseInRegion(const std::vector<CameraParams>& readings, const FieldRect& region,
                              const std::string& basis, int width, int height);

// Given field points fix the half; the twin is what the same clicks would
// give with the coordinates' signs flipped.
SymmetryDecision decidedByPoints(const CameraParams& p, int width, int height);

}  // namespace dv

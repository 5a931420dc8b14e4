#pragma once
// The id of a robot seen with side blobs missing: two ids fit one missing
// blob, four fit two (a robot at the image border). Ids are unique per
// team, so the ids that fully seen teammates hold are ruled out.
#include <vector>

#include "detection/robot_hypothesis.h"

namespace dv {

// For every robot of `robots` not seen whole (Hypothesis::seen_sides), the
// first id left after its fully seen teammates' (the missing blobs taken as
// their colors guess them before the other color), written to colors and
// id; id_known where exactly one is left. A robot seen whole gets id_known.
void resolvePartialIds(std::vector<Hypothesis>& robots);

}  // namespace dv

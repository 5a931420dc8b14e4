#pragma once
// `dotvision eval --plot DIR`: what a reviewer would rather look at than
// read. Histograms of the robots' position and orientation errors and of
// the balls' position errors, and a field map of where robots and balls
// were missed, misidentified or detected where there was none.
#include <string>
#include <vector>

#include "eval/metrics.h"

namespace dv {

// Writes robot_position_error.png, robot_orientation_error.png,
// ball_position_error.png (where there are errors) and field_map.png into
// `dir` (created). Returns the files written; throws InputError naming the
// folder or file when one cannot be written.
std::vector<std::string> writeEvalPlots(const std::string& dir, const Metrics& m);

}  // namespace dv

#pragma once
// A plausibility check of the Bayer layout a source was given. A wrong
// --bayer swaps colors everywhere: nothing is detected and nothing else
// says why.
#include <opencv2/core.hpp>
#include <string>

#include "pipeline/pipeline_options.h"

namespace dv {

// Empty when the mosaic agrees with `pattern`; otherwise one sentence naming
// the likely layouts. A field is mostly green carpet, so under any white
// balance a camera's green sites form the brighter diagonal of each 2x2
// cell; the check only speaks when the sites `pattern` calls green are
// clearly darker than the other diagonal.
std::string bayerLayoutWarning(const cv::Mat& raw, BayerPattern pattern);

}  // namespace dv

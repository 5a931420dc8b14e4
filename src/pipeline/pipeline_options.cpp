#include "pipeline/pipeline_options.h"

#include <cctype>
#include <string>

namespace dv {

bool parseBayerPattern(const char* text, BayerPattern& out) {
  std::string s = text ? text : "";
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s == "rggb") out = BayerPattern::RGGB;
  else if (s == "grbg") out = BayerPattern::GRBG;
  else if (s == "gbrg") out = BayerPattern::GBRG;
  else if (s == "bggr") out = BayerPattern::BGGR;
  else if (s == "none" || s == "bgr" || s == "rgb") out = BayerPattern::None;
  else return false;
  return true;
}

const char* bayerPatternName(BayerPattern p) {
  switch (p) {
    case BayerPattern::None: return "none";
    case BayerPattern::RGGB: return "rggb";
    case BayerPattern::GRBG: return "grbg";
    case BayerPattern::GBRG: return "gbrg";
    case BayerPattern::BGGR: return "bggr";
  }
  return "?";
}

}  // namespace dv

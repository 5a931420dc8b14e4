#include "pipeline/pipeline_options.h"

#include <cctype>
#include <string>

namespace dv {

namespace {

std::string lower(const char* text) {
  std::string s = text ? text : "";
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

bool parseBayerPattern(const char* text, BayerPattern& out) {
  const std::string s = lower(text);
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

bool parseBayerSampling(const char* text, BayerSampling& out) {
  const std::string s = lower(text);
  if (s == "auto") out = BayerSampling::Auto;
  else if (s == "subsample") out = BayerSampling::Subsample;
  else if (s == "full") out = BayerSampling::Full;
  else return false;
  return true;
}

const char* bayerSamplingName(BayerSampling s) {
  switch (s) {
    case BayerSampling::Auto: return "auto";
    case BayerSampling::Subsample: return "subsample";
    case BayerSampling::Full: return "full";
  }
  return "?";
}

}  // namespace dv

#pragma once
// What the camera does to the light that reaches it: uneven illumination
// across the image, exposure, white balance and flicker gains, lens blur,
// read and shot noise, clipping to 8 bits and the Bayer mosaic (any of the four layouts).
#include <cstdint>
#include <opencv2/core.hpp>

#include "synth/scene.h"

namespace dv {

// Brightness multiplier of the uneven illumination for every pixel (CV_32F):
// a smooth exponential ramp, brightest / darkest = ratio across the image.
cv::Mat unevenLightMap(int width, int height, double ratio, double direction);

// Multiplies `map` (CV_32F) by the vignetting falloff 1 - v (r / r_corner)^2,
// r measured from the image center.
void applyVignetting(cv::Mat& map, double vignetting);

// Mean of 1 + a sin(2 pi f s) over the exposure [t - T/2, t + T/2].
double flickerGain(const SceneLighting& l, double t);

struct SensorSettings {
  double gain[3] = {1, 1, 1};  // per channel, B, G, R (exposure x white balance x flicker)
  double saturation = 1;       // mix with luma after the gains (SceneLighting)
  double gamma = 1;
  double lens_blur_px = 0;
  double noise_sigma = 0;      // read noise, 8-bit levels
  double shot_noise = 0;       // variance per level of signal
  bool bayer = true;
  BayerLayout layout = BayerLayout::RGGB;
  uint64_t noise_seed = 1;
};

// radiance: CV_32FC3 (B, G, R, 0..255 scale), modified in place (gains,
// blur). uneven: CV_32F map or empty. Returns CV_8UC1 Bayer in s.layout or
// CV_8UC3 BGR.
cv::Mat applySensor(cv::Mat& radiance, const cv::Mat& uneven, const SensorSettings& s);

}  // namespace dv

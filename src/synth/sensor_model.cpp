#include "synth/sensor_model.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "synth/random.h"

namespace dv {

cv::Mat unevenLightMap(int width, int height, double ratio, double direction) {
  cv::Mat map(height, width, CV_32F);
  const double c = std::cos(direction), s = std::sin(direction);
  // Project the image corners on the direction to normalise the ramp to
  // [-1/2, 1/2] over the image.
  double lo = 1e300, hi = -1e300;
  for (int cu : {0, width - 1})
    for (int cv_ : {0, height - 1}) {
      const double p = cu * c + cv_ * s;
      lo = std::min(lo, p), hi = std::max(hi, p);
    }
  const double span = std::max(hi - lo, 1e-9), log_ratio = std::log(std::max(ratio, 1e-6));
  for (int v = 0; v < height; ++v) {
    float* row = map.ptr<float>(v);
    for (int u = 0; u < width; ++u)
      row[u] = float(std::exp(log_ratio * ((u * c + v * s - lo) / span - 0.5)));
  }
  return map;
}

void applyVignetting(cv::Mat& map, double vignetting) {
  const double cu = 0.5 * (map.cols - 1), cv_ = 0.5 * (map.rows - 1);
  const double k = vignetting / std::max(cu * cu + cv_ * cv_, 1e-9);
  for (int v = 0; v < map.rows; ++v) {
    float* row = map.ptr<float>(v);
    for (int u = 0; u < map.cols; ++u)
      row[u] *= float(1 - k * ((u - cu) * (u - cu) + (v - cv_) * (v - cv_)));
  }
}

double flickerGain(const SceneLighting& l, double t) {
  if (l.flicker_amplitude == 0) return 1;
  const double w = 2 * kPi * l.flicker_frequency;
  const double x = 0.5 * w * l.exposure_time;
  const double sinc = std::abs(x) < 1e-9 ? 1 : std::sin(x) / x;
  return 1 + l.flicker_amplitude * std::sin(w * t) * sinc;
}

namespace {

// Saturation about the pixel's luma (BT.601 weights), then gamma on 0..255.
void applyColorProcessing(cv::Mat& radiance, double saturation, double gamma) {
  const float s = static_cast<float>(saturation);
  for (int v = 0; v < radiance.rows; ++v) {
    float* p = radiance.ptr<float>(v);
    for (int u = 0; u < radiance.cols; ++u, p += 3) {
      const float y = 0.114f * p[0] + 0.587f * p[1] + 0.299f * p[2];
      for (int c = 0; c < 3; ++c) {
        float x = std::max(0.0f, y + s * (p[c] - y));
        if (gamma != 1) x = static_cast<float>(255.0 * std::pow(std::min(x, 255.0f) / 255.0, gamma));
        p[c] = x;
      }
    }
  }
}

}  // namespace

cv::Mat applySensor(cv::Mat& radiance, const cv::Mat& uneven, const SensorSettings& s) {
  const int rows = radiance.rows, cols = radiance.cols;
  for (int v = 0; v < rows; ++v) {
    float* p = radiance.ptr<float>(v);
    const float* m = uneven.empty() ? nullptr : uneven.ptr<float>(v);
    for (int u = 0; u < cols; ++u) {
      const float k = m ? m[u] : 1.0f;
      p[3 * u + 0] *= float(s.gain[0]) * k;
      p[3 * u + 1] *= float(s.gain[1]) * k;
      p[3 * u + 2] *= float(s.gain[2]) * k;
    }
  }
  if (s.saturation != 1 || s.gamma != 1) applyColorProcessing(radiance, s.saturation, s.gamma);
  if (s.lens_blur_px > 0) cv::GaussianBlur(radiance, radiance, cv::Size(0, 0), s.lens_blur_px);

  SplitMix64 rng(s.noise_seed);
  auto sensorValue = [&](float signal) {
    double value = signal;
    const double var = s.noise_sigma * s.noise_sigma + s.shot_noise * std::max(0.0, value);
    if (var > 0) value += std::sqrt(var) * rng.normal();
    return cv::saturate_cast<uint8_t>(std::lround(std::clamp(value, 0.0, 255.0)));
  };
  if (s.bayer) {
    // Red site within the 2x2 cell; blue is diagonally opposite.
    const int rx = s.layout == BayerLayout::GRBG || s.layout == BayerLayout::BGGR;
    const int ry = s.layout == BayerLayout::GBRG || s.layout == BayerLayout::BGGR;
    cv::Mat out(rows, cols, CV_8UC1);
    for (int v = 0; v < rows; ++v) {
      const float* p = radiance.ptr<float>(v);
      uint8_t* o = out.ptr<uint8_t>(v);
      for (int u = 0; u < cols; ++u) {
        // BGR storage: 2 = R, 1 = G, 0 = B.
        const bool xr = (u & 1) == rx, yr = (v & 1) == ry;
        const int channel = xr && yr ? 2 : (!xr && !yr ? 0 : 1);
        o[u] = sensorValue(p[3 * u + channel]);
      }
    }
    return out;
  }
  cv::Mat out(rows, cols, CV_8UC3);
  for (int v = 0; v < rows; ++v) {
    const float* p = radiance.ptr<float>(v);
    uint8_t* o = out.ptr<uint8_t>(v);
    for (int i = 0; i < 3 * cols; ++i) o[i] = sensorValue(p[i]);
  }
  return out;
}

}  // namespace dv

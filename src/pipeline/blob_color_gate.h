#pragma once
// Which peaks are colored enough to be a league blob. Pattern dots and the
// ball are strongly colored; white line crossings and gray features make
// blob-shaped chroma edges only from the carpet around them. "Colored" is
// judged against the frame itself, so that no camera setting moves it:
//  - the frame's neutral is the color of its white lines (known places on
//    the field): colors are compared after the white balance that makes the
//    lines gray, so a tungsten or cold-LED cast neither colors the lines nor
//    grays out the markers (and the lines' color is the cast the camera's
//    white balance should remove: reported to the operator);
//  - the saturation needed scales with the frame's own: a share of what its
//    most colored peaks show (a desaturating camera or gamma lowers every
//    saturation alike), never less than a line crossing would show (line
//    and carpet as read beside the lines) nor more than kMinBlobSaturation.
//    A frame whose lines are not where the geometry puts them keeps the
//    fixed kMinBlobSaturation.
// The same peaks give the frame's marker contrast: how far, in the pixel
// pipeline's chroma, its most colored blobs lie from the carpet (what the
// fast-ball pass weighs a streak against, streak_windows.h).
// Both backends judge their peaks with it. No allocation after construction.
#include <opencv2/core.hpp>
#include <vector>

#include "core/units.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "pipeline/blob.h"
#include "pipeline/kernels.h"
#include "pipeline/pipeline_options.h"

namespace dv {

class BlobColorGate {
 public:
  // Sample points along the field lines (z = 0) that the camera sees.
  BlobColorGate(const CameraModel& camera, const FieldModel& field);
  // The pixel pipeline's chroma axes (dRGB unless set), for markerContrast.
  void setChroma(const ChromaTransform& t) { chroma_ = t; }

  // First, per frame: the lines' color from `raw` (Bayer or BGR).
  void measureNeutral(const cv::Mat& raw, BayerPattern bayer);
  // Or take another gate's measurement of the same frame (the coarse pass's).
  void adoptNeutral(const BlobColorGate& other);
  // Then the frame's saturation scale from its strong peaks' colors
  // (addPeak for each, strongest first), before any peak is judged.
  void beginPeaks() {
    peak_saturation_.clear();
    peak_contrast_.clear();
  }
  void addPeak(const float rgb[3]);
  void endPeaks();
  // Whether a blob of mean color rgb is colored enough.
  bool colored(const float rgb[3]) const { return saturation(rgb) >= threshold_; }
  // (max - min) / max of rgb after the white balance the lines give.
  float saturation(const float rgb[3]) const;

  // Squared distance of two colors in the pixel pipeline's chroma axes
  // (0..255 rgb units, before the white balance).
  float chromaDistance2(const float x[3], const float y[3]) const;

  const NeutralColor& neutral() const { return neutral_; }
  // The median carpet beside the lines (invalid where the lines were not
  // seen: then the samples need not be carpet).
  CarpetColor carpet() const {
    CarpetColor c;
    c.valid = carpet_valid_ && neutral_.valid;
    for (int k = 0; k < 3; ++k) c.rgb[k] = carpet_rgb_[k];
    return c;
  }
  float threshold() const { return threshold_; }
  // After endPeaks: the squared chroma distance (chroma axes, 0..255 rgb)
  // from the carpet of the most colored of the frame's colored strong
  // peaks; divided by the squared mean luma it is in the streak pass's
  // units. 0 where the lines, the carpet or too few colored peaks were
  // seen, or where the lines clip in two channels (their cast is then
  // unknown).
  float markerContrast() const { return marker_contrast_; }
  int linePoints() const { return static_cast<int>(points_.size()); }

 private:
  std::vector<ImagePx> points_;  // image px of line samples
  std::vector<ImagePx> carpet_;  // image px of the carpet beside each
  std::vector<float> bright_;    // per sample: r + g + b (reused)
  std::vector<float> rgb_;       // per sample (reused)
  std::vector<float> order_;     // brightness copy for the quantile (reused)
  std::vector<float> peak_saturation_;
  std::vector<float> peak_contrast_;  // per peak, alongside peak_saturation_
  std::vector<float> scratch_;  // for quantiles (reused)
  ChromaTransform chroma_ = ChromaTransform::of(ColorSpace::DRGB);
  float carpet_rgb_[3] = {0, 0, 0};  // median carpet beside the lines
  bool carpet_valid_ = false;
  bool lines_clipped_ = false;  // two channels of the lines' color at the sensor's top
  float marker_contrast_ = 0;
  NeutralColor neutral_;
  float gain_[3] = {1, 1, 1};
  float threshold_ = 0;
  float line_saturation_ = 0;  // of a line-carpet mix: what a crossing shows
};

}  // namespace dv

#pragma once
// Field-line pixels (thesis §5.1.4): the ridge detector of eq. 5.9. A pixel
// is a line pixel when it is brighter by more than a threshold than both
// pixels at the half line width on either side, horizontally or vertically.
// Wide bright areas (walls, robots' tops, goals) and single edges give no
// response, which keeps clutter off the field low.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/units.h"

namespace dv {

struct LinePixelOptions {
  // Distance to the side pixels: half the expected line width in pixels,
  // rounded up, plus one so that the side pixels lie off the line.
  int half_width_px = 3;
  // Brightness step (0..255) a line must have over both sides.
  int threshold = 18;
  // Rejects coloured pixels (robot markers, ball): max-min channel spread
  // above this is not white. Only used for colour input.
  int max_colour_spread = 80;
};

// 8-bit single channel is a Bayer RGGB mosaic (as a `run` source); 3 channel
// is BGR. Returns BGR. Throws InputError(source, ...) for other formats.
cv::Mat toBgrImage(const cv::Mat& image, const std::string& source);
// A decoded image file as `run` takes it (Bayer mosaic kept as it is, colour
// as BGR); throws InputError(source, ...) for an unsupported format.
cv::Mat calibrationImage(const cv::Mat& decoded, const std::string& source);
// Brightness for line detection. A Bayer mosaic is filtered with the 3x3
// binomial kernel, which weighs R, G, B as 1:2:1 at every pixel, so thin
// lines keep their shape instead of the colour fringes of demosaicing.
cv::Mat lineBrightness(const cv::Mat& image);

// The half line width for the ridge detector from the expected field scale
// (mm per pixel) and the painted line thickness (mm).
int halfLineWidthPx(double mm_per_px, double line_thickness_mm);

// CV_8UC1 mask, 255 at line pixels. `image` is a Bayer mosaic (CV_8UC1) or
// BGR (CV_8UC3).
cv::Mat detectLinePixels(const cv::Mat& image, const LinePixelOptions& options);

// Coordinates of the mask's set pixels, thinned to at most `max_count` by a
// regular stride so that they stay spread over the image.
std::vector<ImagePx> maskPixels(const cv::Mat& mask, size_t max_count);

// Moves each line pixel across its line to the line's centre at sub-pixel
// precision: along the row or column on which the ridge is stronger, the
// brightness profile is climbed to its top and followed down to its feet,
// and the centroid of the brightness above the straight baseline between
// the feet taken. A mask pixel is an integer position anywhere within the
// painted width, so without this a line centre scatters by a third of the
// width (0.3-0.7 px) and the fits and their predicted error carry that.
// `gray` is lineBrightness() of the image; pixels within a few line widths
// of the border keep their place.
void refineToLineCentres(const cv::Mat& gray, int half_width_px, std::vector<ImagePx>& pixels);

}  // namespace dv

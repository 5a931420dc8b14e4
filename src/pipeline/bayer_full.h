#pragma once
// Full Bayer sampling: the 2x2 subsampling of bayer_subsample.h done for
// every 2x2 window of the mosaic instead of every other one, so sample
// (x, y) describes full pixel (x + 0.5, y + 0.5) and there are as many
// samples as pixels. Each window holds one red, one blue and two green
// sites; green is the mean of the two greens, red and blue are moved half a
// pixel to the window center with bilinear weights 9:3:3:1 on their own
// 2-pixel lattice. Every sample has the same filter, only mirrored, so the
// channels stay co-sited and positions unbiased (a plain bilinear demosaic
// alternates between copied and averaged values from pixel to pixel, which
// the color gradient would see as zipper edges). The sample at even (x, y)
// is exactly the subsampled sample (x / 2, y / 2).
//
// At the image border a site beyond the edge is replaced by the one two
// pixels back (same color); the last row and column of samples, whose
// windows reach past the image, are thereby defined too.
#include <cstdint>
#include <opencv2/core.hpp>

#include "pipeline/bayer_subsample.h"
#include "pipeline/pipeline_options.h"

namespace dv {

// raw: CV_8UC1 mosaic of even size. Writes rows [row_begin, row_end),
// columns [col_begin, col_end) of the raw.cols x raw.rows image of packed
// chroma pairs (as bayerChromaRows).
void fullBayerChromaRows(const cv::Mat& raw, BayerPattern pattern, const ChromaFixed& k,
                         uint32_t* packed, int row_begin, int row_end, int col_begin, int col_end);

// A rectangle of samples: columns [x_begin, x_end), rows [y_begin, y_end).
struct SampleRegion {
  int x_begin = 0, x_end = 0, y_begin = 0, y_end = 0;
};
// The 2x2 cells under a region of full samples. The frame brightness is
// measured on cells in both samplings (under subsampling they are the samples).
inline SampleRegion fullBayerCells(const SampleRegion& s) {
  return {s.x_begin / 2, (s.x_end + 1) / 2, s.y_begin / 2, (s.y_end + 1) / 2};
}

// Co-sited RGB of sample (x, y) (clamped to the image), for blob colors and
// inspection views.
void fullBayerRgbAt(const cv::Mat& raw, BayerPattern pattern, int x, int y, float rgb[3]);

}  // namespace dv

#pragma once
// A Bayer mosaic at half size with the same layout: each pixel of the
// output is the mean of the four pixels of its site in one 4x4 block of the
// input (each 2x2 cell of the output one block). Subsampling the
// output's 2x2 cells then gives one color sample per 4x4 block: the samples
// of the coarse search (coarse_search.h).
#include <opencv2/core.hpp>

namespace dv {

// raw: CV_8UC1, width and height multiples of 4. out: CV_8UC1 of half the
// size (allocated by the caller). Writes output cell rows
// [cell_begin, cell_end), i.e. output pixel rows 2 * cell_begin ... .
void binMosaicRows(const cv::Mat& raw, cv::Mat& out, int cell_begin, int cell_end);

}  // namespace dv

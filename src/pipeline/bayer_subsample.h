#pragma once
// Bayer 2x2 subsampling (thesis §5.2.3): each 2x2 cell becomes one RGB pixel.
// Unlike plain subsampling, the red and blue samples (which sit a quarter
// cell off the cell center, on opposite sides) are interpolated to the cell
// center, so all three channels describe the same point (2i+0.5, 2j+0.5) in
// full-image pixels. Without this, blue and red blobs shift by about half a
// full pixel diagonally.
#include <cstdint>
#include <opencv2/core.hpp>

#include "pipeline/pipeline_options.h"

namespace dv {

// raw: CV_8UC1 mosaic of even size. Writes rows [row_begin, row_end), columns
// [col_begin, col_end) (-1 = to the end) of the (cols/2) x (rows/2) RGBX
// image `rgbx` (4 bytes per pixel, X = 0).
void subsampleBayerRows(const cv::Mat& raw, BayerPattern pattern, uint8_t* rgbx, int row_begin,
                        int row_end, int col_begin = 0, int col_end = -1);

// raw: CV_8UC3 BGR. Writes that part of the same-size RGBX image.
void bgrToRgbxRows(const cv::Mat& raw, uint8_t* rgbx, int row_begin, int row_end,
                   int col_begin = 0, int col_end = -1);

// Chroma with integer coefficients (1/1024 units), for the packed form below.
struct ChromaFixed {
  int a[3], b[3];
};

// Same subsampling, but each sample is written as its two chroma values
// (x1024 coefficients, >> 4, i.e. chroma * 64) packed as int16 pairs
// (a in the low half). This is what the rectification reads; keeping only
// two 16-bit channels halves its arithmetic.
void bayerChromaRows(const cv::Mat& raw, BayerPattern pattern, const ChromaFixed& k,
                     uint32_t* packed, int row_begin, int row_end, int col_begin, int col_end);
// The same values stored transposed: sample (i, j) at packed_t[i * stride + j],
// stride >= rows / 2 (for grids whose rows run along image columns; see
// RemapTable::transposed).
void bayerChromaRowsTransposed(const cv::Mat& raw, BayerPattern pattern, const ChromaFixed& k,
                               uint32_t* packed_t, size_t stride, int row_begin, int row_end,
                               int col_begin, int col_end);
// Samples i in [i_begin, i_end), j in [j_begin, j_end) (inside the
// subsampled image) into a box of their own: sample (i, j) at
// out[(j - j_begin) * stride + i - i_begin], or at
// out[(i - i_begin) * stride + j - j_begin] when transposed. The values are
// those of bayerChromaRows.
void bayerChromaBox(const cv::Mat& raw, BayerPattern pattern, const ChromaFixed& k, bool transposed,
                    uint32_t* out, size_t stride, int i_begin, int i_end, int j_begin, int j_end);
void bgrChromaRows(const cv::Mat& raw, const ChromaFixed& k, uint32_t* packed, int row_begin,
                   int row_end, int col_begin, int col_end);
constexpr float kPackedChromaScale = 64.0f;

// Bilinear weights 9:3:3:1 (/16) move a sample a quarter cell (half a pixel)
// in x and y toward its neighbours nx, ny, nxy.
inline int quarterShift(int c, int nx, int ny, int nxy) { return (9 * c + 3 * nx + 3 * ny + nxy + 8) >> 4; }

// One sample's two chroma values (see bayerChromaRows), packed.
inline uint32_t packChroma(const ChromaFixed& k, int r, int g, int b) {
  const int a = (k.a[0] * r + k.a[1] * g + k.a[2] * b + 8) >> 4;
  const int c = (k.b[0] * r + k.b[1] * g + k.b[2] * b + 8) >> 4;
  return (static_cast<uint32_t>(a) & 0xffffu) | (static_cast<uint32_t>(c) << 16);
}

// Co-sited RGB of one sample (i, j) (clamped to the image), for the few places
// that need color after the frame: blob colors and inspection views.
// raw: the Bayer mosaic (pattern != None) or the BGR image.
void sampleRgbAt(const cv::Mat& raw, BayerPattern pattern, int i, int j, float rgb[3]);

// Where the red and blue samples of a pattern sit inside the 2x2 cell
// (x = column offset, y = row offset, each 0 or 1).
struct BayerSites {
  int rx, ry, bx, by;
};
BayerSites bayerSites(BayerPattern pattern);

}  // namespace dv

#pragma once
// Per-frame loops of the CPU pipeline, each over a range of rows so that the
// thread pool can split them. No allocation, no exceptions.
#include <cstdint>
#include <limits>
#include <vector>

#include "pipeline/pipeline_options.h"
#include "pipeline/remap_table.h"

namespace dv {

#if defined(__x86_64__)
// Whether the hand-written AVX2 paths may run (the build is generic x86-64).
inline bool cpuHasAvx2() {
  static const bool yes = __builtin_cpu_supports("avx2");
  return yes;
}
#endif

// Chroma transform applied to the interpolated color. Two channels suffice:
// dRGB (R - (G+B)/2, ...) is 1.5 times the projection onto the plane normal
// to gray, so its gradient dot product equals that of two orthonormal chroma
// axes scaled by 1.5; YUV uses U and V (luma edges are what we suppress).
struct ChromaTransform {
  float a[3], b[3];
  static ChromaTransform of(ColorSpace space);
};

// Rectify rows [y_begin, y_end) of the grid: bilinear interpolation of the
// packed chroma samples (see bayerChromaRows; chroma is linear, so
// interpolating it equals converting interpolated color), times `gain`.
// The interpolation is exact integer arithmetic (1/256 weights, x then y),
// then one float product by gain / 2^16.
// Writes planes ca, cb (grid sized, row-major).
void rectifyChromaRows(const RemapTable& table, const uint32_t* packed, float gain, float* ca,
                       float* cb, int y_begin, int y_end);
// The same for n cells given by their own table entries: sample indices into
// `packed` (row stride `stride`) and fractions; results to ca[0..n), cb[0..n).
void rectifyChromaCells(const int32_t* index, const uint16_t* frac, int stride, const uint32_t* packed,
                        float gain, float* ca, float* cb, size_t n);

// Color gradient dot product (thesis eq. 5.11, §5.2.7.1) at distance `scale`
// cells (fractional distances interpolate linearly), summed over both chroma
// channels, in fixed point (value * 2^14). Cells closer than the gradient
// reach to the border are 0.
constexpr float kGradientFixedPoint = 16384.0f;
void gradientDotRows(const float* ca, const float* cb, int width, int height, double scale,
                     int32_t* g, int y_begin, int y_end);
// Row y alone, into out[0..width).
void gradientDotRow(const float* ca, const float* cb, int width, int height, double scale, int y,
                    int32_t* out);

// The same from five row pointers per plane, rows y - k - 1, y - k, y,
// y + k, y + k + 1 with k = floor(scale); the row must be inside the plane's
// gradient reach (gradientDotRow makes the zero rows).
void gradientDotRowFrom(const float* const a_rows[5], const float* const b_rows[5], int width, double scale,
                        int32_t* out);

// The whitened product of view_stretch.h: per cell the quadratic form
// a gx^2 + b gx gy + c gy^2 summed over both channels, (a, b, c) the first
// three of the 6 floats per kFormBlock cells of `forms` (one block row).
void gradientFormRowFrom(const float* const a_rows[5], const float* const b_rows[5], int width, double scale,
                         const float* forms, int32_t* out);

// Mean gradient energy 1/2 sum_c (gx^2 + gy^2) over the (2r+1)^2 cells around
// (x, y), same gradient as gradientDotRows. Used only at peak candidates.
// Stops early and returns give_up_above once the energy is known to exceed it
// (callers that only compare against a limit need not sum the whole window).
float windowGradientEnergy(const float* ca, const float* cb, int width, double scale, int x, int y,
                           int r, float give_up_above = std::numeric_limits<float>::infinity());

// The same with the energy form q = (qxx, qxy, qyy) of view_stretch.h:
// 1/2 sum_c qxx gx^2 + 2 qxy gx gy + qyy gy^2, summed in the same order.
float windowGradientEnergyForm(const float* ca, const float* cb, int width, double scale, int x, int y, int r,
                               const float q[3], float give_up_above = std::numeric_limits<float>::infinity());

// Summed-area table (thesis A.3) in modular 32-bit arithmetic: a box sum is
// exact whenever its true value fits in 32 bits, whatever the table values.
// `sat` is (width+1) x (height+1), row 0 and column 0 zero.
// The table sums the 2x2 box of G (sum of four cells), which puts table cell
// (x, y) at position (x + 1/2, y + 1/2): quadrants around a grid cell then
// meet on the cell's own row and column instead of leaving that row and
// column out. A left-out row and column make the score flat within one cell
// of the center, and quadratic interpolation on a flat top is biased.
// Pass 1: row prefix sums of rows [y_begin, y_end).
void satRowPrefixRows(const int32_t* g, int width, int height, uint32_t* sat, int y_begin,
                      int y_end);
// Table row y + 1 of pass 1 (the prefix of box row y) into out[0..width].
void satRowPrefixRow(const int32_t* g, int width, int height, int y, uint32_t* out);
// The same from the two G rows of the box, r0 above r1.
void boxRowPrefix(const int32_t* r0, const int32_t* r1, int width, uint32_t* out);
// The same plus the table row above it (above[0..width]): the next row of
// the summed-area table in one pass.
void boxRowPrefixOnto(const int32_t* r0, const int32_t* r1, int width, const uint32_t* above, uint32_t* out);
// Pass 2: column prefix over columns [x_begin, x_end) of the table.
void satColumnPrefix(uint32_t* sat, int width, int height, int x_begin, int x_end);

// Minimum quadrant sum score (thesis eq. 5.15) with square quadrants of
// `r` cells, from the summed-area table, divided by r^2 and the fixed point
// (so the score is the mean G over the weakest quadrant).
// Cells without a full window are 0.
// The inner q x q corner of each quadrant (next to the center) is left out:
// where two field lines cross, the gradient dot product forms the same
// checkerboard as a blob, but only within about one gradient distance of the
// crossing, while a blob's response lies on its rim. q = 0 keeps the thesis's
// full quadrants.
void quadrantMinScoreRows(const uint32_t* sat, int width, int height, int r, int q, float* score,
                          int y_begin, int y_end);

// The same scores straight from the chroma planes: each band of rows makes
// its G rows (gradientDotRow at `scale`), their table rows (pass 1) and
// sums the columns from its own origin r rows above it, in a ring of
// 2r + 1 rows (`scratch`, sized on first use), so neither G nor the table is
// written out or read back. Equal to gradientDotRows, satRowPrefixRows,
// satColumnPrefix and quadrantMinScoreRows in turn, bit for bit.
// `forms` (view_stretch.h, may be null): the whitened product where a
// block is not plain.
struct GradientForms;
void quadrantMinScoreFromChroma(const float* ca, const float* cb, int width, int height, double scale,
                                int r, int q, float* score, int y_begin, int y_end,
                                std::vector<uint32_t>& scratch, const GradientForms* forms = nullptr);

// Where a score pass reads its chroma rows: two whole planes, or rows that a
// band makes as they are asked for (rows are asked for in rising order, the
// highest of a gradient row first; a band asks only within its rows plus
// the reach of the score window and the gradient).
class ChromaRowSource {
 public:
  virtual void rows(int y, const float*& a, const float*& b) = 0;

 protected:
  ~ChromaRowSource() = default;
};
// Told of each score row as soon as it is written (rising order), so that
// work on the row can run while it is in cache.
class ScoreRowSink {
 public:
  virtual void rowDone(int y) = 0;

 protected:
  ~ScoreRowSink() = default;
};
// quadrantMinScoreFromChroma with the chroma rows from `src`; `sink`, when
// given, hears of every row that gets a score (not the zero rows at the
// plane's edges).
void quadrantMinScoreFromRows(ChromaRowSource& src, int width, int height, double scale, int r, int q,
                              float* score, int y_begin, int y_end, std::vector<uint32_t>& scratch,
                              const GradientForms* forms = nullptr, ScoreRowSink* sink = nullptr);

// Exact circular quadrants of radius `radius` cells, from row prefix sums
// (pass 1 only). Each quadrant is the quarter disc of the half-offset cells
// whose centers lie within `radius`, divided by its cell count.
void circleMinScoreRows(const uint32_t* row_prefix, int width, int height, double radius,
                        float* score, int y_begin, int y_end);

}  // namespace dv

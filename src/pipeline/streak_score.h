#pragma once
// Fast balls: a ball rolling faster than about 5 m/s is a streak during the
// exposure (6.5 m/s over 8 ms: 52 mm longer than its 43 mm diameter, its
// color diluted toward the ends), which the round blob score no longer
// finds. This pass looks for short colored streaks on a coarse copy of the
// chroma planes, color-agnostic like the blob score: at four orientations
// the mean chroma of a short run along the streak (inner) must differ, in
// the same direction, from each of four samples around it, two across the
// streak and two beyond its ends. Lines (same chroma beyond the ends),
// edges and corners (same chroma on one side) fail; a ball in any motion,
// including at rest, passes. Which colors are balls is left to the
// detector's ball policy, which sees these candidates only as balls.
//
// The reported position is the centroid of the streak's excess chroma over
// the surround along the inner direction: chroma is linear in the exposure
// a cell received from the ball, so for a ball rolling straight the centroid
// is its mid-exposure position (the capture time).
#include <cstdint>

#include <vector>

#include "core/units.h"
#include "pipeline/blob.h"
#include "pipeline/blob_color_gate.h"
#include "pipeline/streak_windows.h"

namespace dv {


// Lattice cells whose footprint lies within the camera's view: `valid` (grid
// sized, 1 = seen) eroded by the footprint's reach, read at their centers.
std::vector<uint8_t> streakPeakMask(const uint8_t* valid, int grid_width, int grid_height, const StreakWindows& w);

// Means of the first grid row of each factor x factor box (factor cells)
// into coarse rows [cy_begin, cy_end) of `coarse` (interleaved a, b pairs,
// coarse_width per row). Grid cells beyond the last full box are left out.
void streakCoarseRows(const float* ca, const float* cb, int width, const StreakWindows& w, float* coarse,
                      int cy_begin, int cy_end);

// Streak score of lattice rows [j_begin, j_end) into lattice-sized planes:
// where the gate passes (levels.gate), for each orientation, with I the
// inner mean, S_k the four surround samples, D_k = I - S_k and D their
// mean, min_k (D_k . D) / (mean_k |D_k|^2 + levels.floor); the best
// orientation's score and index. Cells within the margin are 0.
void streakScoreRows(const float* coarse, const StreakWindows& w, const StreakLevels& levels, float* score,
                     uint8_t* orientation, int j_begin, int j_end);

// A local maximum of the lattice score (3x3, strict toward the top-left as
// findPeakRows) above kStreakThreshold where mask (lattice sized) allows,
// in lattice rows [j_begin, j_end); appends (x, y: lattice cell, score) to
// out[count..capacity) and returns the new count.
struct StreakPeak {
  int x = 0, y = 0;
  float score = 0;
};
// The order candidates are taken in: strongest first, then by row and
// column (a total order, so both searches take equal lists alike).
inline bool strongerStreak(const StreakPeak& a, const StreakPeak& b) {
  if (a.score != b.score) return a.score > b.score;
  return a.y != b.y ? a.y < b.y : a.x < b.x;
}
int findStreakPeakRows(const float* score, const uint8_t* mask, const StreakWindows& w, StreakPeak* out,
                       int count, int capacity, int j_begin, int j_end);

// Centroid (grid cells) of the chroma excess over the surround of the
// streak at lattice peak p: weight max(0, (c - B) . (I - B) / |I - B|^2 -
// 0.25) over the cells of the footprint rectangle, with I and B the inner
// and surround means of the peak's orientation. The peak's center
// where no cell has weight.
GridPx refineStreak(const float* ca, const float* cb, int width, int height, const float* coarse,
                    const StreakWindows& w, const StreakPeak& p, int orientation);

// What refineStreak weighs the cells by: the footprint rectangle (center,
// unit direction along the streak, half lengths along and across, in grid
// cells) and the chroma projection (background ba, bb; ka, kb the inner
// minus background over its squared length). `ok`: false where inner and
// background have the same chroma (the center is then the answer).
struct StreakFit {
  double cx = 0, cy = 0, ux = 1, uy = 0, along = 0, across = 0;
  float ba = 0, bb = 0, ka = 0, kb = 0;
  bool ok = false;
};
StreakFit streakFit(const float* coarse, const StreakWindows& w, const StreakPeak& p, int orientation);
// The centroid of the fit's weights over cells [x0, x0 + width) x
// [y0, y0 + height) of chroma planes ca, cb (row stride `width`; the fit's
// coordinates are the whole grid's).
GridPx streakCentroid(const StreakFit& fit, const float* ca, const float* cb, int x0, int y0, int width, int height);

// Grid position of a lattice peak's cell center.
GridPx streakPeakCenter(const StreakWindows& w, const StreakPeak& p);
// Whether a blob of `blobs` lies within `distance_mm` of g: a peak there is
// that blob (checked before the refinement, to spare it, and after).
bool nearBlob(const std::vector<Blob>& blobs, GridPx g, double grid_scale,
              double distance_mm = kStreakBlobDistanceMm);

// Whether a streak blob (position and color set) joins `blobs`: not within
// kStreakBlobDistanceMm of any blob there (an object the blob score found,
// or a stronger streak), colored enough for `colors` (as blobs), and fewer
// than kMaxStreakBlobs streaks so far. Both backends use it.
bool acceptStreakBlob(const std::vector<Blob>& blobs, const Blob& streak, double grid_scale,
                      const BlobColorGate& colors);

}  // namespace dv

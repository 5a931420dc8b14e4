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

namespace dv {

// Footprint in mm: the inner run reaches this far along the streak from its
// center, the side samples lie this far across it, the end samples this far
// along it. The ends clear a ball's 21.5 mm radius plus half the streak of
// 8 m/s over 8 ms (32 mm); the sides clear the radius plus half a coarse cell.
inline constexpr double kStreakInnerMm = 16;
inline constexpr double kStreakSideMm = 34;
inline constexpr double kStreakEndMm = 64;
// Coarse cell side (mm), about a quarter of the ball's diameter.
inline constexpr double kStreakCellMm = 11;
// Threshold on the streak score (see streakScoreRows). A clean streak of
// contrast |D| scores |D|^2 / (|D|^2 + kStreakFloor): on the motion preset
// (60 frames) the 34 balls found as streaks scored 0.70..0.88 (|D|^2 about
// 4), so 0.45 still takes a ball at half that contrast (a shadow); the 8
// streak blobs that were not balls (goal corners) scored 0.45..0.49 and
// were left to the ball policy, which took none. Carpet texture scores
// below 0.1.
inline constexpr float kStreakThreshold = 0.45f;
// Added to the mean squared contrast before the ratio (brightness-normalised
// chroma units): texture whose contrast is small against the ball's cannot
// reach high scores (at 0.02, 8700 carpet cells of one frame scored above
// the threshold and crowded the ball out of the candidate lists).
inline constexpr float kStreakFloor = 1.0f;
// Cells are scored only where the cell's chroma differs from the mean of
// four cells around it (the axis-aligned end samples) by more than this
// (squared, brightness-normalised chroma): a score above kStreakThreshold
// needs a contrast of about kStreakThreshold * kStreakFloor, and most of
// the field is plain carpet far below.
inline constexpr float kStreakGate = 0.2f;
// A streak candidate within this distance of a blob is that blob.
inline constexpr double kStreakBlobDistanceMm = 30;

inline constexpr int kStreakOrientations = 4;  // 0, 45, 90, 135 degrees
// The score is evaluated at every other coarse cell in x and y (22 mm
// apart): a streak's score plateau is wider than that, and its position
// comes from the centroid, not from the peak cell. A quarter of the work.
inline constexpr int kStreakLatticeStep = 2;
// Candidates per band of rows, and streak blobs per frame (a field holds
// one ball; the rest are for the ball policy to reject).
inline constexpr int kMaxStreakCandidates = 256;
inline constexpr int kMaxStreakBlobs = 32;

// The footprint on a grid of `scale` mm per cell, in coarse cells.
struct StreakWindows {
  int factor = 2;  // grid cells per coarse cell side
  int coarse_width = 0, coarse_height = 0;
  // Score lattice: lattice cell (i, j) is coarse cell (2i, 2j).
  int lattice_width = 0, lattice_height = 0;
  // Per orientation: unit step (dx, dy) along the streak; the step across is
  // (-dy, dx). Inner run -inner..inner steps, sides at +-side, ends at +-end.
  int step_x[kStreakOrientations] = {1, 1, 0, -1};
  int step_y[kStreakOrientations] = {0, 1, 1, 1};
  int inner[kStreakOrientations] = {1, 1, 1, 1};
  int side[kStreakOrientations] = {3, 2, 3, 2};
  int end[kStreakOrientations] = {6, 4, 6, 4};
  int margin = 7;  // coarse cells at the edge without a full footprint
  int gate_reach = 6;  // coarse cells to the gate's samples (along the axes)
  // Refinement window on the grid: half extents along and across (cells).
  float refine_along = 10, refine_across = 5;
};
StreakWindows streakWindows(double grid_scale, int grid_width, int grid_height);

// Lattice cells whose footprint lies within the camera's view: `valid` (grid
// sized, 1 = seen) eroded by the footprint's reach, read at their centers.
std::vector<uint8_t> streakPeakMask(const uint8_t* valid, int grid_width, int grid_height, const StreakWindows& w);

// Means of the first grid row of each factor x factor box (factor cells)
// into coarse rows [cy_begin, cy_end) of `coarse` (interleaved a, b pairs,
// coarse_width per row). Grid cells beyond the last full box are left out.
void streakCoarseRows(const float* ca, const float* cb, int width, const StreakWindows& w, float* coarse,
                      int cy_begin, int cy_end);

// Streak score of lattice rows [j_begin, j_end) into lattice-sized planes:
// where the gate passes
// (kStreakGate), for each orientation, with
// I the inner mean, S_k the four surround samples, D_k = I - S_k and D their
// mean, min_k (D_k . D) / (mean_k |D_k|^2 + kStreakFloor); the best
// orientation's score and index. Cells within the margin are 0.
void streakScoreRows(const float* coarse, const StreakWindows& w, float* score, uint8_t* orientation,
                     int j_begin, int j_end);

// A local maximum of the lattice score (3x3, strict toward the top-left as
// findPeakRows) above kStreakThreshold where mask (lattice sized) allows,
// in lattice rows [j_begin, j_end); appends (x, y: lattice cell, score) to
// out[count..capacity) and returns the new count.
struct StreakPeak {
  int x = 0, y = 0;
  float score = 0;
};
int findStreakPeakRows(const float* score, const uint8_t* mask, const StreakWindows& w, StreakPeak* out,
                       int count, int capacity, int j_begin, int j_end);

// Centroid (grid cells) of the chroma excess over the surround of the
// streak at lattice peak p: weight max(0, (c - B) . (I - B) / |I - B|^2 -
// 0.25) over the cells of the footprint rectangle, with I and B the inner
// and surround means of the peak's orientation. The peak's center
// where no cell has weight.
GridPx refineStreak(const float* ca, const float* cb, int width, int height, const float* coarse,
                    const StreakWindows& w, const StreakPeak& p, int orientation);

// Grid position of a lattice peak's cell center.
GridPx streakPeakCenter(const StreakWindows& w, const StreakPeak& p);
// Whether a blob of `blobs` lies within kStreakBlobDistanceMm of g: a peak
// there is that blob (checked before the refinement, to spare it, and after).
bool nearBlob(const std::vector<Blob>& blobs, GridPx g, double grid_scale);

// Whether a streak blob (position and color set) joins `blobs`: not within
// kStreakBlobDistanceMm of any blob there (an object the blob score found,
// or a stronger streak), strongly colored (kMinBlobSaturation, as blobs),
// and fewer than kMaxStreakBlobs streaks so far. Both backends use it.
bool acceptStreakBlob(const std::vector<Blob>& blobs, const Blob& streak, double grid_scale);

}  // namespace dv

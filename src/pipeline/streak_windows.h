#pragma once
// The fast-ball pass's footprint (see streak_score.h) on a grid of a given
// scale. Plain C++ on purpose: the stand-alone OpenCL benchmark, which links
// no OpenCV, builds its tables from it too.
#include <algorithm>
#include <cmath>

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
// the threshold and crowded the ball out of the candidate lists). Used as
// it stands only where the frame's markers give no scale (streakLevels).
inline constexpr float kStreakFloor = 1.0f;
// Cells are scored only where the cell's chroma differs from the mean of
// four cells around it (the axis-aligned end samples) by more than this
// (squared, brightness-normalised chroma): a score above kStreakThreshold
// needs a contrast of about kStreakThreshold * kStreakFloor, and most of
// the field is plain carpet far below.
inline constexpr float kStreakGate = 0.2f;
// The floor as a share of the frame's marker contrast (the squared chroma
// distance of its most colored strong peaks from the carpet, see
// BlobColorGate::markerContrast): a camera's cast, desaturation or gamma
// shrinks the ball's streak, the carpet's texture and the markers alike, so
// the score weighs the streak against what this frame's colors can show.
// The preset's own colors give a marker contrast of about 9.5 (floor 0.48);
// the ball's streak there has a squared contrast of about 4.
inline constexpr float kStreakFloorShare = 0.05f;

// The floor and gate one frame's streak pass uses.
struct StreakLevels {
  float floor = kStreakFloor, gate = kStreakGate;
  float luma_mean = 0;  // the frame's, which the chroma was divided by (0: unknown)
};
// From the frame's marker contrast in 0..255 rgb units and its mean luma
// (the chroma's brightness normalisation); the fixed levels where either
// is unknown (0). The gate keeps its ratio to the floor.
inline StreakLevels streakLevels(float marker_contrast, float luma_mean) {
  StreakLevels l;
  l.luma_mean = luma_mean > 0 ? luma_mean : 0;
  if (!(marker_contrast > 0) || !(luma_mean > 0)) return l;
  l.floor = kStreakFloorShare * marker_contrast / (luma_mean * luma_mean);
  l.gate = l.floor * (kStreakGate / kStreakFloor);
  return l;
}

// Whether a streak that scored `score` at `levels` would pass the fixed
// floor too. Its squared contrast q follows from the score where the
// footprint fits cleanly (all four surround differences alike: score =
// q / (q + floor)), and a rougher fit only lowers the score, so this is
// the fixed floor's verdict on a clean streak and stricter on a rough one.
inline bool streakPassesFixedFloor(float score, const StreakLevels& levels) {
  if (!(score < 1)) return true;
  const float q = score * levels.floor / (1 - score);
  return q / (q + kStreakFloor) > kStreakThreshold;
}

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

inline StreakWindows streakWindows(double grid_scale, int grid_width, int grid_height) {
  StreakWindows w;
  w.factor = std::max(1, static_cast<int>(std::lround(kStreakCellMm / grid_scale)));
  w.coarse_width = grid_width / w.factor;
  w.coarse_height = grid_height / w.factor;
  w.lattice_width = (w.coarse_width + kStreakLatticeStep - 1) / kStreakLatticeStep;
  w.lattice_height = (w.coarse_height + kStreakLatticeStep - 1) / kStreakLatticeStep;
  const double cell = w.factor * grid_scale;
  w.margin = 1;
  for (int o = 0; o < kStreakOrientations; ++o) {
    const double step = cell * std::hypot(w.step_x[o], w.step_y[o]);
    w.inner[o] = std::max(1, static_cast<int>(std::lround(kStreakInnerMm / step)));
    w.side[o] = std::max(w.inner[o] + 1, static_cast<int>(std::lround(kStreakSideMm / step)));
    w.end[o] = std::max(w.side[o], static_cast<int>(std::lround(kStreakEndMm / step)));
    w.margin = std::max(w.margin, std::max(w.side[o], w.end[o]) + 1);
  }
  w.gate_reach = w.end[0];
  // The centroid window: inside the end and side samples, less a margin for
  // the coarse cell they average.
  w.refine_along = static_cast<float>((kStreakEndMm - 0.5 * cell) / grid_scale);
  w.refine_across = static_cast<float>((kStreakSideMm - 0.5 * cell) / grid_scale);
  return w;
}

}  // namespace dv

#pragma once
// Where the field's markings lie on the rectified grid, for the fast-ball
// pass. The lines are white only under a neutral camera: under a color
// cast, or with the false color a Bayer mosaic gives a line two pixels
// wide, a short stretch of line is a colored bar on the carpet that fits
// the streak footprint, and one frame's lines give dozens of candidates.
// The backends take candidates on a marking after all others, so the lines
// cannot fill the streak list before a ball elsewhere, and those on a
// marking most colored first (saturation after the lines' white balance):
// a stretch of line is a line-carpet mix, no more colored than the carpet,
// while a ball on the line adds its own color (under a cold cast at
// saturation 0.4 the center line's candidates showed 0.3, the ball rolling
// along it 0.6, the carpet 0.34).
// Nor does the frame's marker contrast scale the floor there: the lines'
// chroma under a cast grows with the cast, not with the markers. A
// candidate on a marking passes the fixed floor (streakPassesFixedFloor)
// or is clearly more colored than the carpet (kLineMixSaturationExcess).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "pipeline/blob.h"
#include "pipeline/blob_color_gate.h"
#include "pipeline/rectified_grid.h"
#include "pipeline/streak_score.h"

namespace dv {

// A line's stretch reads up to this many times the carpet's saturation:
// the Bayer mosaic's false colors on a line 2 px wide and a camera's gamma
// bend the mix (tungsten, saturation 0.4, gamma 1.6: up to 1.32 times; the
// ball on the center line under the cold cast: 1.76).
inline constexpr float kLineMixSaturationExcess = 1.5f;

class MarkingMask {
 public:
  MarkingMask() = default;
  // Grid cells (on the plane z = plane_height) that show the field (z = 0)
  // within half the marking's thickness plus one coarse streak cell
  // (kStreakCellMm: where a line's streak centroid may land) of a marking.
  MarkingMask(const CameraModel& camera, const FieldModel& field, const RectifiedGrid& grid, double plane_height);
  bool at(GridPx g) const {
    const int x = static_cast<int>(std::lround(g.x)), y = static_cast<int>(std::lround(g.y));
    return x >= 0 && y >= 0 && x < width_ && y < height_ && cells_[static_cast<size_t>(y) * width_ + x];
  }

 private:
  int width_ = 0, height_ = 0;
  std::vector<uint8_t> cells_;
};

// Takes streak candidates in their order (strongest first) into `blobs` by
// acceptStreakBlob, those on a marking after all the others, most colored
// first, and only where they pass the fixed floor or are clearly more
// colored than the carpet. make(c, blob) fills the candidate's blob (scored
// at `levels`) and returns false to skip it; `later` is scratch (reserved
// by the caller: no allocation per frame).
template <class Candidates, class Make>
void takeStreaksMarkingsLast(const Candidates& candidates, Make make, const MarkingMask& markings,
                             const StreakLevels& levels, std::vector<Blob>& blobs, std::vector<Blob>& later,
                             double grid_scale, const BlobColorGate& colors) {
  later.clear();
  const float carpet = colors.carpetSaturation();
  for (const auto& c : candidates) {
    Blob b;
    if (!make(c, b)) continue;
    if (markings.at(b.grid)) {
      const bool stands_out = streakPassesFixedFloor(b.score, levels) ||
                              (carpet > 0 && colors.saturation(b.rgb) > kLineMixSaturationExcess * carpet);
      if (stands_out && later.size() < later.capacity()) later.push_back(b);
    } else if (acceptStreakBlob(blobs, b, grid_scale, colors)) {
      blobs.push_back(b);
    }
  }
  // A total order, so that both backends take equal lists alike.
  std::sort(later.begin(), later.end(), [&](const Blob& a, const Blob& b) {
    const float sa = colors.saturation(a.rgb), sb = colors.saturation(b.rgb);
    if (sa != sb) return sa > sb;
    if (a.score != b.score) return a.score > b.score;
    return a.grid.y != b.grid.y ? a.grid.y < b.grid.y : a.grid.x < b.grid.x;
  });
  for (const Blob& b : later)
    if (acceptStreakBlob(blobs, b, grid_scale, colors)) blobs.push_back(b);
}

}  // namespace dv

#pragma once
// Where the field's markings lie on the rectified grid, and what they look
// like there, for the fast-ball pass. The lines are white only under a
// neutral camera: under a color cast, or with the false color a Bayer
// mosaic gives a line two pixels wide, a short stretch of line is a
// colored bar on the carpet that fits the streak footprint, and one
// frame's lines give dozens of candidates. The backends take candidates on
// a marking after all others, so the lines cannot fill the streak list
// before a ball elsewhere.
// A candidate on a marking is weighed against the marking itself rather
// than the carpet: its color against the same marking's, seen the same way
// a little further along it (cast, gamma, the mosaic's false colors, the
// light and the line's width alike). A stretch of line matches its
// neighbours; a ball on the line adds its own color. The difference, less
// the marking's own change between the two neighbours, passes as a
// streak's contrast does (at the frame's levels), and candidates are taken
// most distinct first. Where two markings meet, no stretch further
// along either looks like the crossing: there a candidate must pass the
// fixed floor (streakPassesFixedFloor), as under a neutral camera.
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "pipeline/blob.h"
#include "pipeline/blob_color_gate.h"
#include "pipeline/pipeline_options.h"
#include "pipeline/rectified_grid.h"
#include "pipeline/streak_score.h"

namespace dv {

// How far along the marking its own look is read: twice the footprint's
// end reach (kStreakEndMm clears the ball and half its streak at 8 m/s),
// so that the reference's color disc clears the streak by as much again.
inline constexpr double kMarkingLookMm = 128;
// How far on, and in what steps, a stretch in the candidate's own phase on
// the mosaic is looked for (contrastToMarking): four looks, no farther than
// a quarter look apart (a stretch of one phase is longer than that wherever
// its false color is strong enough to make a streak). A ball's own streak
// ends well within the nearest look, so no step finds the ball again.
inline constexpr double kMarkingSpanMm = 4 * kMarkingLookMm;
inline constexpr double kMarkingSpanStepMm = kMarkingLookMm / 4;

// A grid cell's marking: its index (the field's lines, then its arcs; -1:
// none) and whether two markings meet there.
struct MarkingCell {
  int marking = -1;
  bool crossing = false;
};

class MarkingMask {
 public:
  MarkingMask() = default;
  // Grid cells (on the plane z = plane_height) that show the field (z = 0)
  // within half the marking's thickness plus one coarse streak cell
  // (kStreakCellMm: where a line's streak centroid may land) of a marking.
  MarkingMask(const CameraModel& camera, const FieldModel& field, const RectifiedGrid& grid, double plane_height);
  MarkingCell at(GridPx g) const {
    const int x = static_cast<int>(std::lround(g.x)), y = static_cast<int>(std::lround(g.y));
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return {};
    const uint16_t c = cells_[static_cast<size_t>(y) * width_ + x];
    return {static_cast<int>(c & kIndexBits) - 1, (c & kCrossingBit) != 0};
  }
  // The squared chroma distance (colors.chromaDistance2) of the color disc
  // (kColorRadiusMm) around plane point p from the same disc along
  // `marking`, the nearest of those kMarkingLookMm either way and on to
  // kMarkingSpanMm, less the two nearest looks' own difference where both
  // lie in the image; nullopt where neither does.
  std::optional<float> contrastToMarking(const cv::Mat& raw, BayerPattern bayer, const BlobColorGate& colors,
                                         FieldMm p, int marking) const;

 private:
  static constexpr uint16_t kCrossingBit = 0x8000, kIndexBits = 0x7fff;
  // A marking as the plane z = plane_height sees it (the camera's center
  // projects the field's plane onto it: directions are kept, circles stay
  // circles about the projected center).
  struct PlaneMarking {
    bool arc = false;
    FieldMm dir{1, 0};   // line: unit direction
    FieldMm center{0, 0};  // arc: center on the plane
  };
  bool discRgb(const cv::Mat& raw, BayerPattern bayer, FieldMm p, float rgb[3]) const;

  std::optional<CameraModel> camera_;
  double plane_height_ = 0;
  std::vector<PlaneMarking> markings_;
  int width_ = 0, height_ = 0;
  std::vector<uint16_t> cells_;  // marking index + 1 (0: none), kCrossingBit
};

// A streak candidate on a marking and its contrast to the marking.
struct MarkedStreak {
  Blob blob;
  float contrast = 0;
};

// Whether a candidate on a marking stands out from it: its contrast to the
// marking (nullopt: unknown) weighed as a streak's contrast at `levels`,
// and at a crossing the fixed floor.
inline bool standsOutFromMarking(std::optional<float> contrast, MarkingCell cell, float score,
                                 const StreakLevels& levels) {
  if (!contrast || cell.crossing || !(levels.luma_mean > 0)) return streakPassesFixedFloor(score, levels);
  const float floor = levels.floor * levels.luma_mean * levels.luma_mean;  // in 0..255 chroma units
  return *contrast > 0 && *contrast / (*contrast + floor) > kStreakThreshold;
}

// Takes streak candidates in their order (strongest first) into `blobs` by
// acceptStreakBlob, those on a marking after all the others, most distinct
// from the marking first, and only where they stand out from it.
// make(c, blob) fills the candidate's blob (scored at `levels`) and returns
// false to skip it; `later` is scratch (reserved by the caller: no
// allocation per frame). raw: the frame (Bayer mosaic or BGR).
template <class Candidates, class Make>
void takeStreaksMarkingsLast(const Candidates& candidates, Make make, const MarkingMask& markings,
                             const cv::Mat& raw, BayerPattern bayer, const StreakLevels& levels,
                             std::vector<Blob>& blobs, std::vector<MarkedStreak>& later, double grid_scale,
                             const BlobColorGate& colors) {
  later.clear();
  for (const auto& c : candidates) {
    Blob b;
    if (!make(c, b)) continue;
    const MarkingCell cell = markings.at(b.grid);
    if (cell.marking >= 0) {
      const auto contrast = markings.contrastToMarking(raw, bayer, colors, b.position, cell.marking);
      if (standsOutFromMarking(contrast, cell, b.score, levels) && later.size() < later.capacity())
        later.push_back({b, contrast.value_or(0)});
    } else if (acceptStreakBlob(blobs, b, grid_scale, colors)) {
      blobs.push_back(b);
    }
  }
  // A total order, so that both backends take equal lists alike.
  std::sort(later.begin(), later.end(), [](const MarkedStreak& a, const MarkedStreak& b) {
    if (a.contrast != b.contrast) return a.contrast > b.contrast;
    if (a.blob.score != b.blob.score) return a.blob.score > b.blob.score;
    return a.blob.grid.y != b.blob.grid.y ? a.blob.grid.y < b.blob.grid.y : a.blob.grid.x < b.blob.grid.x;
  });
  for (const MarkedStreak& m : later)
    if (acceptStreakBlob(blobs, m.blob, grid_scale, colors)) blobs.push_back(m.blob);
}

}  // namespace dv

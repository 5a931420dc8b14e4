// The fast-ball pass weighed against the frame's own colors: the streak
// floor follows the markers' contrast (streak_windows.h, BlobColorGate), and
// candidates on the field's markings are taken last, most colored first
// (streak_markings.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "geometry/camera_model.h"
#include "pipeline/blob_color_gate.h"
#include "pipeline/rectified_grid.h"
#include "pipeline/streak_markings.h"
#include "pipeline/streak_score.h"
#include "synth/renderer.h"

namespace dv {
namespace {

// The lattice score at the center of a streak of chroma (a, b) on a plain
// carpet of chroma 0, with every chroma value scaled by `s`.
float centerScore(float a, float b, float s, const StreakLevels& levels) {
  const StreakWindows w = streakWindows(5.6, 400, 400);
  std::vector<float> coarse(2 * static_cast<size_t>(w.coarse_width) * w.coarse_height, 0);
  const int cx = w.coarse_width / 2 & ~1, cy = w.coarse_height / 2 & ~1;  // a lattice cell
  for (int x = cx - w.inner[0]; x <= cx + w.inner[0]; ++x) {
    float* c = &coarse[2 * (static_cast<size_t>(cy) * w.coarse_width + x)];
    c[0] = a * s, c[1] = b * s;
  }
  std::vector<float> score(static_cast<size_t>(w.lattice_width) * w.lattice_height);
  std::vector<uint8_t> orientation(score.size());
  streakScoreRows(coarse.data(), w, levels, score.data(), orientation.data(), 0, w.lattice_height);
  return score[static_cast<size_t>(cy / kStreakLatticeStep) * w.lattice_width + cx / kStreakLatticeStep];
}

TEST(StreakLevels, ADesaturatedFrameScoresItsStreakAsTheNeutralOne) {
  // A streak of squared contrast 2 in a frame whose markers show 9.5 (the
  // preset's own colors; luma 1 for brevity).
  const float marker = 9.5f;
  const float nominal = centerScore(1.0f, 1.0f, 1.0f, streakLevels(marker, 1));
  EXPECT_GT(nominal, kStreakThreshold);
  // A camera at saturation 0.4 scales every chroma, the markers' included.
  const float s = 0.4f;
  EXPECT_NEAR(centerScore(1.0f, 1.0f, s, streakLevels(marker * s * s, 1)), nominal, 1e-5);
  // The fixed floor loses it.
  EXPECT_LT(centerScore(1.0f, 1.0f, s, StreakLevels{}), kStreakThreshold);
  // Brightness: the chroma planes are divided by the frame's mean luma.
  const StreakLevels bright = streakLevels(marker, 2), dark = streakLevels(marker, 1);
  EXPECT_FLOAT_EQ(bright.floor * 4, dark.floor);
  EXPECT_FLOAT_EQ(bright.gate / bright.floor, kStreakGate / kStreakFloor);
}

TEST(StreakLevels, WithoutAMarkerContrastTheLevelsAreTheFixedOnes) {
  for (const StreakLevels l : {streakLevels(0, 100), streakLevels(5, 0)}) {
    EXPECT_EQ(l.floor, kStreakFloor);
    EXPECT_EQ(l.gate, kStreakGate);
  }
}

SceneSpec& exposed(SceneSpec& s, double exposure, double saturation) {
  s.lighting.exposure = exposure;
  s.lighting.saturation = saturation;
  return s;
}

// A rendered top-down frame, its camera, and a gate that has read its lines.
struct Frame {
  SceneSpec spec = presetScene("top_down_div_b_half");
  RenderedFrame frame;
  CameraModel camera;
  BlobColorGate gate;
  explicit Frame(double exposure = 1, double saturation = 1)
      : frame(Renderer(exposed(spec, exposure, saturation)).render(0, 0)),
        camera(spec.cameras[0].calib),
        gate(camera, spec.field) {
    gate.measureNeutral(frame.image, spec.bayer ? BayerPattern::RGGB : BayerPattern::None);
  }
};

float markerContrast(BlobColorGate& gate, const std::vector<std::vector<float>>& peaks) {
  gate.beginPeaks();
  for (const auto& p : peaks) gate.addPeak(p.data());
  gate.endPeaks();
  return gate.markerContrast();
}

TEST(StreakLevels, TheMarkerContrastIsTheColoredPeaksDistanceFromTheCarpet) {
  Frame f;
  ASSERT_TRUE(f.gate.neutral().valid);
  const std::vector<float> pink{240, 60, 160}, pale{170, 130, 150};
  const float vivid = markerContrast(f.gate, {pink, pink, pink, pink});
  EXPECT_GT(vivid, 0);
  // Paler markers: a smaller contrast (and so a lower streak floor).
  const float paler = markerContrast(f.gate, {pale, pale, pale, pale});
  EXPECT_GT(paler, 0);
  EXPECT_LT(paler, vivid);
  // Fewer colored peaks than one robot's pattern: unknown.
  EXPECT_EQ(markerContrast(f.gate, {pink, pink, pink}), 0);
  // Gray peaks (line crossings) are not markers.
  const std::vector<float> gray{150, 150, 150};
  EXPECT_EQ(markerContrast(f.gate, {gray, gray, gray, gray, pink}), 0);
  // Lines clipped white: the cast, and so the scale, unknown.
  Frame bright(3.0);
  ASSERT_TRUE(bright.gate.neutral().valid);
  ASSERT_GE(std::min({bright.gate.neutral().rgb[0], bright.gate.neutral().rgb[1], bright.gate.neutral().rgb[2]}),
            250);
  EXPECT_EQ(markerContrast(bright.gate, {pink, pink, pink, pink}), 0);
}

TEST(StreakMarkings, TheMaskCoversTheLinesAsTheGridSeesThem) {
  Frame f;
  const double plane = 150;
  const RectifiedGrid grid = *computeRectifiedGrid(f.camera, f.spec.field, plane, 2);
  const MarkingMask mask(f.camera, f.spec.field, grid, plane);
  // Points of the field at z = 0, seen on the grid's plane.
  auto onGrid = [&](double x, double y) {
    const auto p = f.camera.imageToField(*f.camera.fieldToImage({x, y, 0}), plane);
    return grid.toGrid({p->x, p->y});
  };
  const FieldLine& l = f.spec.field.lines.front();
  const double mx = (l.p1.x + l.p2.x) / 2, my = (l.p1.y + l.p2.y) / 2;
  ASSERT_TRUE(f.camera.fieldToImage({mx, my, 0}));
  EXPECT_TRUE(mask.at(onGrid(mx, my)));
  // 60 mm beside the line: carpet.
  const double len = std::hypot(l.p2.x - l.p1.x, l.p2.y - l.p1.y);
  const double nx = -(l.p2.y - l.p1.y) / len, ny = (l.p2.x - l.p1.x) / len;
  EXPECT_FALSE(mask.at(onGrid(mx + 60 * nx, my + 60 * ny)) && mask.at(onGrid(mx - 60 * nx, my - 60 * ny)));
  // The grid's center is not on a line everywhere: most of the field is carpet.
  int marked = 0, cells = 0;
  for (int y = 0; y < grid.height; y += 7)
    for (int x = 0; x < grid.width; x += 7) marked += mask.at({double(x), double(y)}), ++cells;
  EXPECT_LT(marked, cells / 5);
}

TEST(StreakMarkings, LinesCannotFillTheStreakListBeforeABallElsewhere) {
  Frame f;
  f.gate.beginPeaks();
  f.gate.endPeaks();
  // A mask with its left half on a marking.
  const double plane = 150;
  const RectifiedGrid grid = *computeRectifiedGrid(f.camera, f.spec.field, plane, 2);
  const MarkingMask mask(f.camera, f.spec.field, grid, plane);
  std::vector<GridPx> on, off;
  for (int y = 10; y < grid.height - 10 && (on.size() < 40 || off.empty()); y += 12)
    for (int x = 10; x < grid.width - 10; x += 12) {
      if (mask.at({double(x), double(y)})) on.push_back({double(x), double(y)});
      else if (off.empty()) off.push_back({double(x), double(y)});
    }
  ASSERT_GE(on.size(), static_cast<size_t>(kMaxStreakBlobs) + 1);
  ASSERT_EQ(off.size(), 1u);
  const float line[3] = {120, 190, 150}, ball[3] = {230, 120, 40};
  ASSERT_TRUE(f.gate.colored(ball));
  ASSERT_TRUE(f.gate.colored(line));
  ASSERT_GT(f.gate.saturation(ball), f.gate.saturation(line));
  // Stronger streaks on the lines (all colored enough to pass the gate),
  // the ball elsewhere, weakest.
  struct Candidate {
    GridPx at;
    float score;
    const float* rgb;
  };
  std::vector<Candidate> candidates;
  for (size_t i = 0; i < on.size(); ++i) candidates.push_back({on[i], 0.9f - 0.001f * i, ball});
  candidates.push_back({off[0], 0.5f, ball});
  std::vector<Blob> blobs, later;
  later.reserve(candidates.size());
  auto make = [&](const Candidate& c, Blob& b) {
    b.grid = c.at;
    b.position = grid.toField(c.at);
    b.score = c.score;
    b.streak = true;
    std::copy(c.rgb, c.rgb + 3, b.rgb);
    return true;
  };
  takeStreaksMarkingsLast(candidates, make, mask, StreakLevels{}, blobs, later, grid.scale, f.gate);
  ASSERT_EQ(blobs.size(), static_cast<size_t>(kMaxStreakBlobs));
  EXPECT_EQ(blobs.front().grid.x, off[0].x);
  EXPECT_EQ(blobs.front().grid.y, off[0].y);

  // On the markings, the most colored first: a ball on a line outranks the
  // line-carpet mixes around it whatever their scores.
  candidates.clear();
  for (size_t i = 0; i + 1 < on.size(); ++i) candidates.push_back({on[i], 0.9f, line});
  candidates.push_back({on.back(), 0.5f, ball});
  blobs.clear();
  takeStreaksMarkingsLast(candidates, make, mask, StreakLevels{}, blobs, later, grid.scale, f.gate);
  ASSERT_FALSE(blobs.empty());
  EXPECT_EQ(blobs.front().grid.x, on.back().x);
  EXPECT_EQ(blobs.front().grid.y, on.back().y);
}

TEST(StreakMarkings, OnAMarkingAStreakMustStandOutAsUnderTheFixedFloor) {
  Frame f(1, 0.4);  // a desaturating camera: the carpet pale too
  f.gate.beginPeaks();
  f.gate.endPeaks();
  ASSERT_GT(f.gate.carpetSaturation(), 0);
  const double plane = 150;
  const RectifiedGrid grid = *computeRectifiedGrid(f.camera, f.spec.field, plane, 2);
  const MarkingMask mask(f.camera, f.spec.field, grid, plane);
  GridPx on{-1, -1}, off{-1, -1};
  for (int y = 10; y < grid.height - 10; y += 5)
    for (int x = 10; x < grid.width - 10; x += 5) (mask.at({double(x), double(y)}) ? on : off) = {double(x), double(y)};
  ASSERT_GE(on.x, 0);
  ASSERT_GE(off.x, 0);
  // A frame whose markers give a floor a tenth of the fixed one: a streak
  // scoring 0.6 there has a squared contrast of 0.15, which the fixed floor
  // scores 0.13.
  const StreakLevels low{0.1f * kStreakFloor, 0.1f * kStreakGate};
  ASSERT_FALSE(streakPassesFixedFloor(0.6f, low));
  ASSERT_TRUE(streakPassesFixedFloor(0.6f, StreakLevels{}));
  const float carpet_like[3] = {120, 190, 150}, vivid[3] = {240, 120, 30};
  ASSERT_TRUE(f.gate.colored(carpet_like));
  ASSERT_LT(f.gate.saturation(carpet_like), kLineMixSaturationExcess * f.gate.carpetSaturation());
  ASSERT_GT(f.gate.saturation(vivid), kLineMixSaturationExcess * f.gate.carpetSaturation());
  auto taken = [&](GridPx at, const float rgb[3], const StreakLevels& levels) {
    struct Candidate {
      GridPx at;
    };
    std::vector<Candidate> one{{at}};
    std::vector<Blob> blobs, later;
    later.reserve(1);
    takeStreaksMarkingsLast(
        one,
        [&](const Candidate& c, Blob& b) {
          b.grid = c.at;
          b.position = grid.toField(c.at);
          b.score = 0.6f;
          b.streak = true;
          std::copy(rgb, rgb + 3, b.rgb);
          return true;
        },
        mask, levels, blobs, later, grid.scale, f.gate);
    return blobs.size() == 1;
  };
  EXPECT_TRUE(taken(off, carpet_like, low));
  EXPECT_FALSE(taken(on, carpet_like, low));
  EXPECT_TRUE(taken(on, carpet_like, StreakLevels{}));
  EXPECT_TRUE(taken(on, vivid, low));
}

}  // namespace
}  // namespace dv

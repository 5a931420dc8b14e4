// The fast-ball pass weighed against the frame's own colors: the streak
// floor follows the markers' contrast (streak_windows.h, BlobColorGate), and
// candidates on the field's markings are taken last and only where they
// stand out from the marking itself (streak_markings.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
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

// The ball's center plane: a ball at rest lies where the grid puts it.
constexpr double kBallPlane = 21.5;

// Where two of the field's lines meet inside the image (for the crossing flag).
std::optional<FieldMm> visibleCrossing(const Frame& f) {
  const auto& lines = f.spec.field.lines;
  for (size_t i = 0; i < lines.size(); ++i)
    for (size_t k = i + 1; k < lines.size(); ++k) {
      const FieldLine &a = lines[i], &b = lines[k];
      const double ax = a.p2.x - a.p1.x, ay = a.p2.y - a.p1.y, bx = b.p2.x - b.p1.x, by = b.p2.y - b.p1.y;
      const double den = ax * by - ay * bx;
      if (std::abs(den) < 1e-9) continue;
      const double t = ((b.p1.x - a.p1.x) * by - (b.p1.y - a.p1.y) * bx) / den;
      const double u = ((b.p1.x - a.p1.x) * ay - (b.p1.y - a.p1.y) * ax) / den;
      if (t < 0.1 || t > 0.9 || u < 0.1 || u > 0.9) continue;  // a crossing, not a corner
      const FieldMm p{a.p1.x + t * ax, a.p1.y + t * ay};
      const auto px = f.camera.fieldToImage({p.x, p.y, 0});
      if (px && px->u > 100 && px->v > 100 && px->u < f.frame.image.cols - 100 && px->v < f.frame.image.rows - 100)
        return p;
    }
  return std::nullopt;
}

// The field's center line (between the goals) and a point a quarter along
// it: in the half-field camera's view, away from the other markings.
size_t centerLineIndex(const FieldModel& field) {
  for (size_t i = 0; i < field.lines.size(); ++i)
    if (field.lines[i].name == "CenterLine") return i;
  return 0;
}
FieldMm quarterAlong(const FieldLine& l) {
  return {l.p1.x + 0.25 * (l.p2.x - l.p1.x), l.p1.y + 0.25 * (l.p2.y - l.p1.y)};
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
  const size_t index = centerLineIndex(f.spec.field);
  const FieldLine& l = f.spec.field.lines[index];
  const double mx = quarterAlong(l).x, my = quarterAlong(l).y;
  ASSERT_TRUE(f.camera.fieldToImage({mx, my, 0}));
  EXPECT_EQ(mask.at(onGrid(mx, my)).marking, static_cast<int>(index));
  EXPECT_FALSE(mask.at(onGrid(mx, my)).crossing);
  // 60 mm beside the line: carpet.
  const double len = std::hypot(l.p2.x - l.p1.x, l.p2.y - l.p1.y);
  const double nx = -(l.p2.y - l.p1.y) / len, ny = (l.p2.x - l.p1.x) / len;
  EXPECT_FALSE(mask.at(onGrid(mx + 60 * nx, my + 60 * ny)).marking >= 0 &&
               mask.at(onGrid(mx - 60 * nx, my - 60 * ny)).marking >= 0);
  // Where two lines cross, both are there.
  const auto crossing = visibleCrossing(f);
  ASSERT_TRUE(crossing);
  EXPECT_TRUE(mask.at(onGrid(crossing->x, crossing->y)).crossing);
  // The grid's center is not on a line everywhere: most of the field is carpet.
  int marked = 0, cells = 0;
  for (int y = 0; y < grid.height; y += 7)
    for (int x = 0; x < grid.width; x += 7) marked += mask.at({double(x), double(y)}).marking >= 0, ++cells;
  EXPECT_LT(marked, cells / 5);
}

// A top-down frame under a green cast with the ball at rest on a line,
// 400 mm from the quarter point of the center line.
struct BallOnLine {
  Frame f;
  FieldMm line_point, ball;
  RectifiedGrid grid;
  MarkingMask mask;
  BayerPattern bayer;
  int index = 0;  // of the center line
  static SceneSpec& withBall(SceneSpec& s) {
    s.lighting.white_balance = {0.8, 1.3, 0.8};
    s.lighting.saturation = 0.7;
    const FieldLine& l = s.field.lines[centerLineIndex(s.field)];
    const double len = std::hypot(l.p2.x - l.p1.x, l.p2.y - l.p1.y);
    s.ball.position = {quarterAlong(l).x + 400 * (l.p2.x - l.p1.x) / len,
                       quarterAlong(l).y + 400 * (l.p2.y - l.p1.y) / len, kBallPlane};
    s.robots.clear();
    return s;
  }
  BallOnLine() : f(), grid(), bayer(f.spec.bayer ? BayerPattern::RGGB : BayerPattern::None) {
    withBall(f.spec);
    f.frame = Renderer(f.spec).render(0, 0);
    f.gate.measureNeutral(f.frame.image, bayer);
    index = static_cast<int>(centerLineIndex(f.spec.field));
    line_point = quarterAlong(f.spec.field.lines[static_cast<size_t>(index)]);
    ball = {f.spec.ball.position.x, f.spec.ball.position.y};
    grid = *computeRectifiedGrid(f.camera, f.spec.field, kBallPlane, 2);
    mask = MarkingMask(f.camera, f.spec.field, grid, kBallPlane);
  }
  // The point where the grid's plane shows the field's point p (z = 0).
  FieldMm onPlane(FieldMm p) const {
    const auto q = f.camera.imageToField(*f.camera.fieldToImage({p.x, p.y, 0}), kBallPlane);
    return {q->x, q->y};
  }
};

TEST(StreakMarkings, ABallOnALineStandsOutFromTheLineAndTheLineDoesNot) {
  BallOnLine s;
  ASSERT_TRUE(s.f.gate.neutral().valid);
  const FieldMm line = s.onPlane(s.line_point);
  const MarkingCell at_line = s.mask.at(s.grid.toGrid(line)), at_ball = s.mask.at(s.grid.toGrid(s.ball));
  ASSERT_EQ(at_line.marking, s.index);
  ASSERT_EQ(at_ball.marking, s.index);
  ASSERT_FALSE(at_line.crossing || at_ball.crossing);
  const auto on_line = s.mask.contrastToMarking(s.f.frame.image, s.bayer, s.f.gate, line, s.index);
  const auto on_ball = s.mask.contrastToMarking(s.f.frame.image, s.bayer, s.f.gate, s.ball, s.index);
  ASSERT_TRUE(on_line && on_ball);
  // At the fixed levels of a frame of mean luma 100.
  const StreakLevels levels = streakLevels(0, 100);
  EXPECT_TRUE(standsOutFromMarking(on_ball, at_ball, 0.6f, levels)) << *on_ball;
  EXPECT_FALSE(standsOutFromMarking(on_line, at_line, 0.6f, levels)) << *on_line;
  // A stretch of line is what the line looks like further along.
  EXPECT_LT(*on_line, 0.05f * *on_ball) << *on_line << " " << *on_ball;
}

TEST(StreakMarkings, LinesCannotFillTheStreakListAndABallElsewhereComesFirst) {
  BallOnLine s;
  s.f.gate.beginPeaks();
  s.f.gate.endPeaks();
  // Stretches of the line (plane points every 30 mm along it, away from
  // the ball), then the ball on it, then a candidate on the carpet, weakest.
  const FieldLine& l = s.f.spec.field.lines[static_cast<size_t>(s.index)];
  const double len = std::hypot(l.p2.x - l.p1.x, l.p2.y - l.p1.y);
  const double dx = (l.p2.x - l.p1.x) / len, dy = (l.p2.y - l.p1.y) / len;
  std::vector<FieldMm> at;
  for (int k = -20; k < 20; ++k)
    at.push_back(s.onPlane({s.line_point.x + 30 * k * dx, s.line_point.y + 30 * k * dy}));
  ASSERT_GE(at.size(), static_cast<size_t>(kMaxStreakBlobs) + 1);
  at.push_back(s.ball);
  at.push_back(s.onPlane({s.line_point.x - 300 * dy, s.line_point.y + 300 * dx}));
  ASSERT_LT(s.mask.at(s.grid.toGrid(at.back())).marking, 0);
  const float colored[3] = {230, 120, 40};
  ASSERT_TRUE(s.f.gate.colored(colored));
  std::vector<Blob> blobs;
  std::vector<MarkedStreak> later;
  later.reserve(at.size());
  takeStreaksMarkingsLast(
      at,
      [&](const FieldMm& p, Blob& b) {
        b.grid = s.grid.toGrid(p);
        b.position = p;
        b.score = &p == &at.back() ? 0.5f : 0.9f;
        b.streak = true;
        std::copy(colored, colored + 3, b.rgb);  // all colored enough for the gate
        return true;
      },
      s.mask, s.f.frame.image, s.bayer, streakLevels(0, 100), blobs, later, s.grid.scale, s.f.gate);
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_NEAR(blobs[0].position.x, at.back().x, 1e-9);
  EXPECT_NEAR(blobs[1].position.x, s.ball.x, 1e-9);
  EXPECT_NEAR(blobs[1].position.y, s.ball.y, 1e-9);
}

TEST(StreakMarkings, AtACrossingAStreakMustPassTheFixedFloor) {
  // A frame whose markers give a floor a tenth of the fixed one: a streak
  // scoring 0.6 there has a squared contrast of 0.15, which the fixed floor
  // scores 0.13.
  const StreakLevels low = streakLevels(0.1f * kStreakFloor / kStreakFloorShare, 1);
  ASSERT_FLOAT_EQ(low.floor, 0.1f * kStreakFloor);
  ASSERT_FALSE(streakPassesFixedFloor(0.6f, low));
  ASSERT_TRUE(streakPassesFixedFloor(0.6f, streakLevels(0, 1)));
  const MarkingCell line{0, false}, crossing{0, true};
  const float vivid = 1000;  // far beyond the floor (0.1 in these units)
  EXPECT_TRUE(standsOutFromMarking(vivid, line, 0.6f, low));
  EXPECT_FALSE(standsOutFromMarking(vivid, crossing, 0.6f, low));
  EXPECT_TRUE(standsOutFromMarking(vivid, crossing, 0.6f, streakLevels(0, 1)));
  // Unknown contrast (the marking's look off the image): the fixed floor.
  EXPECT_FALSE(standsOutFromMarking(std::nullopt, line, 0.6f, low));
  // No more distinct than the marking is from itself along it.
  EXPECT_FALSE(standsOutFromMarking(-5.0f, line, 0.99f, low));
}

}  // namespace
}  // namespace dv

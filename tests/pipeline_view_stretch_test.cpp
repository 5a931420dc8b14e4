// The whitened gradient of tilted views (pipeline/view_stretch.h) and the
// view mask of peaks (score_windows.h, peakMask).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pipeline/kernels.h"
#include "pipeline/rectified_grid.h"
#include "pipeline/score_windows.h"
#include "pipeline/view_stretch.h"
#include "synth/scene.h"

namespace dv {
namespace {

// A camera looking straight down sees blobs round everywhere: no block is
// whitened, so its scores are the plain product's, bit for bit.
TEST(ViewStretch, TopDownCameraIsPlainEverywhere) {
  const SceneSpec spec = presetScene("top_down_div_b_half");
  const CameraModel cam(spec.cameras[0].calib);
  const auto grid = computeRectifiedGrid(cam, spec.field, 150, 2);
  ASSERT_TRUE(grid);
  const GradientForms f = gradientForms(cam, *grid, 150);
  EXPECT_FALSE(f.any);
  // Even at the image corners the stretch is far below a rounding step.
  double d[2];
  const auto corner = cam.imageToField({0, 0}, 150);
  ASSERT_TRUE(corner);
  EXPECT_LT(viewStretch(cam, corner->xy(), 150, d), 1 + kStretchStep / 2);
}

// A camera 1.6 m high at the touch line: near blobs stay round, far ones
// are stretched along the ray from the camera, which the direction follows.
TEST(ViewStretch, SideViewStretchesFarBlobsAlongTheRay) {
  const SceneSpec spec = presetScene("side_view");
  const CameraModel cam(spec.cameras[0].calib);
  const Eigen::Vector3d c = cam.position();
  double d[2];
  // 2 m away: an image pixel is ~1.7 x 2.9 mm, small against the blob.
  EXPECT_LT(viewStretch(cam, {c.x(), c.y() + 2000}, 150, d), 1 + kStretchStep / 2);
  // 5.5 m away, 3 m to the side: ~3.8 x 15 mm per pixel.
  const FieldMm far{c.x() + 3000, c.y() + 4600};
  const double s = viewStretch(cam, far, 150, d);
  EXPECT_GT(s, 1.4);
  EXPECT_LT(s, 2.0);
  const double n = std::hypot(far.x - c.x(), far.y - c.y());
  EXPECT_NEAR(d[0], (far.x - c.x()) / n, 1e-9);
  EXPECT_NEAR(d[1], -(far.y - c.y()) / n, 1e-9);  // grid rows run toward -y
  const auto grid = computeRectifiedGrid(cam, spec.field, 150, 1);
  ASSERT_TRUE(grid);
  const GradientForms f = gradientForms(cam, *grid, 150);
  EXPECT_TRUE(f.any);
  // Plain in front of the camera near it, whitened at the far point.
  const GridPx near = grid->toGrid({c.x(), c.y() + 2000});
  const GridPx at_far = grid->toGrid(far);
  EXPECT_TRUE(f.plainAt(static_cast<int>(near.x), static_cast<int>(near.y)));
  EXPECT_FALSE(f.plainAt(static_cast<int>(at_far.x), static_cast<int>(at_far.y)));
}

// Forms for a whole plane of one stretch s along unit direction d.
GradientForms uniformForms(int width, int height, double s, const double d[2]) {
  GradientForms f;
  f.blocks_x = (width + kFormBlock - 1) / kFormBlock;
  f.blocks_y = (height + kFormBlock - 1) / kFormBlock;
  const size_t n = static_cast<size_t>(f.blocks_x) * f.blocks_y;
  const double k = s - 1, e = 2 * k + k * k;
  const double m1x = 1 + k * d[0] * d[0], m1y = k * d[0] * d[1], m2y = 1 + k * d[1] * d[1];
  const float c[6] = {static_cast<float>(m1x * m1y), static_cast<float>(m1x * m2y + m1y * m1y),
                      static_cast<float>(m1y * m2y), static_cast<float>(1 + e * d[0] * d[0]),
                      static_cast<float>(e * d[0] * d[1]), static_cast<float>(1 + e * d[1] * d[1])};
  for (size_t i = 0; i < n; ++i) f.coef.insert(f.coef.end(), c, c + 6);
  f.plain.assign(n, 0);
  f.plain_row.assign(f.blocks_y, 0);
  f.any = true;
  return f;
}

// A blob stretched 1.7 times along the grid diagonal (as a far side blob of
// the side view): the plain quadrant score loses it, the whitened one,
// with the stretch and direction it was made with, finds it.
TEST(ViewStretch, WhitenedScoreFindsADiagonallyStretchedBlob) {
  const int w = 64, h = 64, cx = 32, cy = 32;
  const double s = 1.7, d[2] = {std::sqrt(0.5), std::sqrt(0.5)};
  std::vector<float> ca(w * h), cb(w * h, 0.f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double u = (x - cx) * d[0] + (y - cy) * d[1], v = -(x - cx) * d[1] + (y - cy) * d[0];
      const double r = std::hypot(u / s, v);  // an ellipse, long along d
      ca[y * w + x] = static_cast<float>(1 / (1 + std::exp((r - 5.5) / 1.2)));  // soft rim
    }
  const double scale = 5.0 / 3;  // gradient distance of a 3.65 mm grid (cells)
  const int r = 7, q = 3;
  std::vector<float> plain(w * h), white(w * h);
  std::vector<uint32_t> scratch;
  quadrantMinScoreFromChroma(ca.data(), cb.data(), w, h, scale, r, q, plain.data(), 0, h, scratch);
  const GradientForms f = uniformForms(w, h, s, d);
  quadrantMinScoreFromChroma(ca.data(), cb.data(), w, h, scale, r, q, white.data(), 0, h, scratch, &f);
  auto ratio = [&](const std::vector<float>& score, const float* form) {
    const float e = form ? windowGradientEnergyForm(ca.data(), cb.data(), w, scale, cx, cy, r, form)
                         : windowGradientEnergy(ca.data(), cb.data(), w, scale, cx, cy, r);
    return score[cy * w + cx] / (e + kEnergyFloor);
  };
  const float threshold = 0.24f;  // PipelineOptions' default
  EXPECT_LT(ratio(plain, nullptr), threshold);
  EXPECT_GT(ratio(white, f.coef.data() + 3), threshold);
  // Identity forms (s = 1) give the plain product.
  const GradientForms one = uniformForms(w, h, 1, d);
  std::vector<float> same(w * h);
  quadrantMinScoreFromChroma(ca.data(), cb.data(), w, h, scale, r, q, same.data(), 0, h, scratch, &one);
  for (int i = 0; i < w * h; ++i) ASSERT_NEAR(same[i], plain[i], 1e-6f) << i;
}

// A peak counts where a side blob's disc is seen; the rest of its window
// may reach past the image border.
TEST(PeakMask, SideBlobDiscMustBeSeen) {
  const int w = 80, h = 60;
  std::vector<uint8_t> valid(w * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < 50; ++x) valid[y * w + x] = 1;  // the image ends at column 50
  const ScoreWindows win = scoreWindows(3.65, BlobScoreKind::QuadrantMin);
  ASSERT_EQ(win.view_reach, 6);  // ceil(20 / 3.65)
  ASSERT_GT(win.margin, win.view_reach);
  const std::vector<uint8_t> m = peakMask(valid, w, h, win);
  const int y = h / 2;
  EXPECT_TRUE(m[y * w + 49 - win.view_reach]);
  EXPECT_FALSE(m[y * w + 50 - win.view_reach]);
  EXPECT_FALSE(m[y * w + win.margin - 1]);  // no full window inside the grid
  EXPECT_TRUE(m[y * w + win.margin]);
}

}  // namespace
}  // namespace dv

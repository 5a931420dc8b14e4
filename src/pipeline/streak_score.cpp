#include "pipeline/streak_score.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "pipeline/score_windows.h"

namespace dv {

StreakWindows streakWindows(double grid_scale, int grid_width, int grid_height) {
  StreakWindows w;
  w.factor = std::max(1, static_cast<int>(std::lround(kStreakCellMm / grid_scale)));
  w.coarse_width = grid_width / w.factor;
  w.coarse_height = grid_height / w.factor;
  const double cell = w.factor * grid_scale;
  w.margin = 1;
  for (int o = 0; o < kStreakOrientations; ++o) {
    const double step = cell * std::hypot(w.step_x[o], w.step_y[o]);
    w.inner[o] = std::max(1, static_cast<int>(std::lround(kStreakInnerMm / step)));
    w.side[o] = std::max(w.inner[o] + 1, static_cast<int>(std::lround(kStreakSideMm / step)));
    w.end[o] = std::max(w.side[o], static_cast<int>(std::lround(kStreakEndMm / step)));
    w.margin = std::max(w.margin, std::max(w.side[o], w.end[o]) + 1);
  }
  // The centroid window: inside the end and side samples, less a margin for
  // the coarse cell they average.
  w.refine_along = static_cast<float>((kStreakEndMm - 0.5 * cell) / grid_scale);
  w.refine_across = static_cast<float>((kStreakSideMm - 0.5 * cell) / grid_scale);
  return w;
}

std::vector<uint8_t> streakPeakMask(const uint8_t* valid, int grid_width, int grid_height, const StreakWindows& w) {
  const int reach = (w.margin + 1) * w.factor;
  const cv::Mat seen(grid_height, grid_width, CV_8UC1, const_cast<uint8_t*>(valid));
  cv::Mat deep;
  cv::erode(seen, deep, cv::getStructuringElement(cv::MORPH_RECT, {2 * reach + 1, 2 * reach + 1}), {-1, -1}, 1,
            cv::BORDER_CONSTANT, 0);
  std::vector<uint8_t> mask(static_cast<size_t>(w.coarse_width) * w.coarse_height, 0);
  const int f = w.factor;
  for (int y = 0; y < w.coarse_height; ++y)
    for (int x = 0; x < w.coarse_width; ++x)
      mask[static_cast<size_t>(y) * w.coarse_width + x] = deep.at<uint8_t>(y * f + f / 2, x * f + f / 2);
  return mask;
}

void streakCoarseRows(const float* ca, const float* cb, int width, const StreakWindows& w, float* coarse,
                      int cy_begin, int cy_end) {
  const int f = w.factor, cw = w.coarse_width;
  const float norm = 1.0f / static_cast<float>(f * f);
  const size_t gw = width;
  for (int cy = cy_begin; cy < cy_end; ++cy) {
    float* out = coarse + 2 * static_cast<size_t>(cy) * cw;
    for (int cx = 0; cx < cw; ++cx) {
      float sa = 0, sb = 0;
      for (int j = 0; j < f; ++j) {
        const size_t row = (static_cast<size_t>(cy) * f + j) * gw + static_cast<size_t>(cx) * f;
        for (int i = 0; i < f; ++i) sa += ca[row + i], sb += cb[row + i];
      }
      out[2 * cx] = sa * norm;
      out[2 * cx + 1] = sb * norm;
    }
  }
}

namespace {

struct Pair {
  float a, b;
};

inline Pair at(const float* coarse, int cw, int x, int y) {
  const float* p = coarse + 2 * (static_cast<size_t>(y) * cw + x);
  return {p[0], p[1]};
}

// Inner mean and the four surround samples of orientation o at (x, y).
inline void footprint(const float* coarse, const StreakWindows& w, int o, int x, int y, Pair& inner,
                      Pair s[4]) {
  const int cw = w.coarse_width;
  const int ux = w.step_x[o], uy = w.step_y[o];
  const int vx = -uy, vy = ux;
  const int n = w.inner[o];
  float ia = 0, ib = 0;
  for (int k = -n; k <= n; ++k) {
    const Pair c = at(coarse, cw, x + k * ux, y + k * uy);
    ia += c.a, ib += c.b;
  }
  const float inv = 1.0f / static_cast<float>(2 * n + 1);
  inner = {ia * inv, ib * inv};
  const int sd = w.side[o], e = w.end[o];
  s[0] = at(coarse, cw, x + sd * vx, y + sd * vy);
  s[1] = at(coarse, cw, x - sd * vx, y - sd * vy);
  s[2] = at(coarse, cw, x + e * ux, y + e * uy);
  s[3] = at(coarse, cw, x - e * ux, y - e * uy);
}

}  // namespace

void streakScoreRows(const float* coarse, const StreakWindows& w, float* score, uint8_t* orientation,
                     int cy_begin, int cy_end) {
  const int cw = w.coarse_width, ch = w.coarse_height, m = w.margin;
  for (int y = cy_begin; y < cy_end; ++y) {
    float* srow = score + static_cast<size_t>(y) * cw;
    uint8_t* orow = orientation + static_cast<size_t>(y) * cw;
    if (y < m || y >= ch - m) {
      std::fill(srow, srow + cw, 0.0f);
      std::fill(orow, orow + cw, uint8_t{0});
      continue;
    }
    for (int x = 0; x < cw; ++x) {
      float best = 0;
      uint8_t best_o = 0;
      if (x >= m && x < cw - m) {
        for (int o = 0; o < kStreakOrientations; ++o) {
          Pair inner, s[4];
          footprint(coarse, w, o, x, y, inner, s);
          float da[4], db[4], ma = 0, mb = 0, sq = 0;
          for (int k = 0; k < 4; ++k) {
            da[k] = inner.a - s[k].a;
            db[k] = inner.b - s[k].b;
            ma += da[k], mb += db[k];
            sq += da[k] * da[k] + db[k] * db[k];
          }
          ma *= 0.25f, mb *= 0.25f;
          float lo = da[0] * ma + db[0] * mb;
          for (int k = 1; k < 4; ++k) lo = std::min(lo, da[k] * ma + db[k] * mb);
          const float v = lo / (0.25f * sq + kStreakFloor);
          if (v > best) best = v, best_o = static_cast<uint8_t>(o);
        }
      }
      srow[x] = best;
      orow[x] = best_o;
    }
  }
}

int findStreakPeakRows(const float* score, const uint8_t* mask, const StreakWindows& w, StreakPeak* out,
                       int count, int capacity, int cy_begin, int cy_end) {
  const int cw = w.coarse_width, ch = w.coarse_height, m = w.margin;
  cy_begin = std::max(cy_begin, m);
  cy_end = std::min(cy_end, ch - m);
  for (int y = cy_begin; y < cy_end; ++y) {
    const float* row = score + static_cast<size_t>(y) * cw;
    for (int x = m; x < cw - m; ++x) {
      const float c = row[x];
      if (!(c > kStreakThreshold) || !mask[static_cast<size_t>(y) * cw + x]) continue;
      // Strict toward the top-left, non-strict toward the bottom-right: a
      // plateau gives one peak.
      bool peak = true;
      for (int dy = -1; dy <= 1 && peak; ++dy)
        for (int dx = -1; dx <= 1 && peak; ++dx) {
          if (!dx && !dy) continue;
          const float n = row[x + static_cast<ptrdiff_t>(dy) * cw + dx];
          const bool before = dy < 0 || (dy == 0 && dx < 0);
          peak = before ? c > n : c >= n;
        }
      if (!peak) continue;
      if (count >= capacity) return count;
      out[count++] = {x, y, c};
    }
  }
  return count;
}

GridPx refineStreak(const float* ca, const float* cb, int width, int height, const float* coarse,
                    const StreakWindows& w, const StreakPeak& p, int orientation) {
  Pair inner, s[4];
  footprint(coarse, w, orientation, p.x, p.y, inner, s);
  const float ba = 0.25f * (s[0].a + s[1].a + s[2].a + s[3].a);
  const float bb = 0.25f * (s[0].b + s[1].b + s[2].b + s[3].b);
  const float da = inner.a - ba, db = inner.b - bb;
  const float d2 = da * da + db * db;
  const double f = w.factor;
  const double cx = p.x * f + 0.5 * (f - 1), cy = p.y * f + 0.5 * (f - 1);
  if (!(d2 > 0)) return {cx, cy};
  const double len = std::hypot(w.step_x[orientation], w.step_y[orientation]);
  const double ux = w.step_x[orientation] / len, uy = w.step_y[orientation] / len;
  const double ra = w.refine_along, rc = w.refine_across;
  const double reach = std::hypot(ra, rc);
  const int x0 = std::max(0, static_cast<int>(std::ceil(cx - reach)));
  const int x1 = std::min(width - 1, static_cast<int>(std::floor(cx + reach)));
  const int y0 = std::max(0, static_cast<int>(std::ceil(cy - reach)));
  const int y1 = std::min(height - 1, static_cast<int>(std::floor(cy + reach)));
  const float ka = da / d2, kb = db / d2;
  double sw = 0, sx = 0, sy = 0;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double ox = x - cx, oy = y - cy;
      const double along = ox * ux + oy * uy, across = -ox * uy + oy * ux;
      if (std::abs(along) > ra || std::abs(across) > rc) continue;
      const size_t k = static_cast<size_t>(y) * width + x;
      const float proj = (ca[k] - ba) * ka + (cb[k] - bb) * kb - 0.25f;
      if (!(proj > 0)) continue;
      sw += proj, sx += proj * ox, sy += proj * oy;
    }
  }
  if (!(sw > 0)) return {cx, cy};
  return {cx + sx / sw, cy + sy / sw};
}

bool acceptStreakBlob(const std::vector<Blob>& blobs, const Blob& streak, double grid_scale) {
  const double near2 = std::pow(kStreakBlobDistanceMm / grid_scale, 2);
  int streaks = 0;
  for (const Blob& b : blobs) {
    const double dx = b.grid.x - streak.grid.x, dy = b.grid.y - streak.grid.y;
    if (dx * dx + dy * dy < near2) return false;
    streaks += b.streak;
  }
  if (streaks >= kMaxStreakBlobs) return false;
  const float hi = std::max({streak.rgb[0], streak.rgb[1], streak.rgb[2]});
  const float lo = std::min({streak.rgb[0], streak.rgb[1], streak.rgb[2]});
  return hi - lo >= kMinBlobSaturation * (hi + 1);
}

}  // namespace dv

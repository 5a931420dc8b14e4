#include "pipeline/streak_score.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "pipeline/kernels.h"
#include "pipeline/score_windows.h"

namespace dv {

std::vector<uint8_t> streakPeakMask(const uint8_t* valid, int grid_width, int grid_height, const StreakWindows& w) {
  const int reach = (w.margin + 1) * w.factor;
  const cv::Mat seen(grid_height, grid_width, CV_8UC1, const_cast<uint8_t*>(valid));
  cv::Mat deep;
  cv::erode(seen, deep, cv::getStructuringElement(cv::MORPH_RECT, {2 * reach + 1, 2 * reach + 1}), {-1, -1}, 1,
            cv::BORDER_CONSTANT, 0);
  std::vector<uint8_t> mask(static_cast<size_t>(w.lattice_width) * w.lattice_height, 0);
  const int f = w.factor * kStreakLatticeStep;
  for (int j = 0; j < w.lattice_height; ++j)
    for (int i = 0; i < w.lattice_width; ++i)
      mask[static_cast<size_t>(j) * w.lattice_width + i] = deep.at<uint8_t>(j * f + w.factor / 2, i * f + w.factor / 2);
  return mask;
}

namespace {

#if defined(__x86_64__)
// Coarse cells [cx, cw) of a row for factor 2: pair sums (hadd adds the
// first of each pair to the second, as the scalar loop does) interleaved
// a, b, written with streaming stores (the row is read only after the pass,
// by when it would have left the cache anyway, so its lines need not be
// fetched first). out + 2 * cx must be 16-byte aligned.
__attribute__((target("avx2"))) int coarsePairsAvx2(const float* a, const float* b, int cx, int cw, float norm,
                                                   float* out) {
  const __m256 k = _mm256_set1_ps(norm);
  for (; cx + 8 <= cw; cx += 8) {
    // Lanes: cells 0 1 4 5 | 2 3 6 7.
    const __m256 sa = _mm256_mul_ps(_mm256_hadd_ps(_mm256_loadu_ps(a + 2 * cx), _mm256_loadu_ps(a + 2 * cx + 8)), k);
    const __m256 sb = _mm256_mul_ps(_mm256_hadd_ps(_mm256_loadu_ps(b + 2 * cx), _mm256_loadu_ps(b + 2 * cx + 8)), k);
    const __m256 lo = _mm256_unpacklo_ps(sa, sb);  // cells 0 1 | 2 3
    const __m256 hi = _mm256_unpackhi_ps(sa, sb);  // cells 4 5 | 6 7
    _mm_stream_ps(out + 2 * cx, _mm256_castps256_ps128(lo));
    _mm_stream_ps(out + 2 * cx + 4, _mm256_extractf128_ps(lo, 1));
    _mm_stream_ps(out + 2 * cx + 8, _mm256_castps256_ps128(hi));
    _mm_stream_ps(out + 2 * cx + 12, _mm256_extractf128_ps(hi, 1));
  }
  _mm_sfence();  // out to other threads before the pool's job ends
  return cx;
}
#endif

}  // namespace

__attribute__((target_clones("avx2", "default"))) void streakCoarseRows(const float* ca, const float* cb, int width,
                                                                         const StreakWindows& w, float* coarse,
                                                                         int cy_begin, int cy_end) {
  const int f = w.factor, cw = w.coarse_width;
  const float norm = 1.0f / static_cast<float>(f);
  const size_t gw = width;
  for (int cy = cy_begin; cy < cy_end; ++cy) {
    // The first grid row of the box only: half the memory traffic of the
    // whole box, and the ball spans many rows.
    const float* a = ca + static_cast<size_t>(cy) * f * gw;
    const float* b = cb + static_cast<size_t>(cy) * f * gw;
    float* out = coarse + 2 * static_cast<size_t>(cy) * cw;
    int cx = 0;
    if (f == 1) {  // the coarse search's grid (pipeline_options.h)
      for (; cx < cw; ++cx) out[2 * cx] = a[cx], out[2 * cx + 1] = b[cx];
      continue;
    }
    if (f == 2) {  // the usual case
      auto cell = [&](int x) {
        out[2 * x] = (a[2 * x] + a[2 * x + 1]) * norm;
        out[2 * x + 1] = (b[2 * x] + b[2 * x + 1]) * norm;
      };
#if defined(__x86_64__)
      if (cpuHasAvx2()) {
        for (; cx < cw && reinterpret_cast<uintptr_t>(out + 2 * cx) % 16; ++cx) cell(cx);
        cx = coarsePairsAvx2(a, b, cx, cw, norm, out);
      }
#endif
      for (; cx < cw; ++cx) cell(cx);
      continue;
    }
    for (; cx < cw; ++cx) {
      float sa = 0, sb = 0;
      for (int i = 0; i < f; ++i) sa += a[cx * f + i], sb += b[cx * f + i];
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

namespace {

// The full score of one cell (all orientations) into best / best_o.
inline void cellScore(const float* coarse, const StreakWindows& w, float contrast_floor, int x, int y, float& best,
                      uint8_t& best_o) {
  best = 0;
  best_o = 0;
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
    const float v = lo / (0.25f * sq + contrast_floor);
    if (v > best) best = v, best_o = static_cast<uint8_t>(o);
  }
}

// Gate of lattice cells i0..i0+n of coarse row y into pass[]: squared
// chroma distance of the cell from the mean of the four cells `r` away along
// the axes (off any ball or streak up to the footprint's length).
__attribute__((target_clones("avx2", "default"))) void gateRow(const float* coarse, int cw, int r, float gate,
                                                               int i0, int n, int y, uint8_t* pass) {
  constexpr int s = 2 * kStreakLatticeStep;  // floats between lattice cells
  const float* c = coarse + 2 * (static_cast<size_t>(y) * cw + static_cast<size_t>(i0) * kStreakLatticeStep);
  const float* up = c - 2 * static_cast<ptrdiff_t>(r) * cw;
  const float* dn = c + 2 * static_cast<ptrdiff_t>(r) * cw;
  for (int i = 0; i < n; ++i) {
    const float ma = 0.25f * (((c[s * i - 2 * r] + c[s * i + 2 * r]) + up[s * i]) + dn[s * i]);
    const float mb = 0.25f * (((c[s * i + 1 - 2 * r] + c[s * i + 1 + 2 * r]) + up[s * i + 1]) + dn[s * i + 1]);
    const float da = c[s * i] - ma, db = c[s * i + 1] - mb;
    pass[i] = da * da + db * db > gate;
  }
}

}  // namespace

void streakScoreRows(const float* coarse, const StreakWindows& w, const StreakLevels& levels, float* score,
                     uint8_t* orientation, int j_begin, int j_end) {
  const int cw = w.coarse_width, ch = w.coarse_height, m = w.margin, lw = w.lattice_width;
  constexpr int kStep = kStreakLatticeStep;
  // Lattice columns whose coarse cell has a full footprint: [i_lo, i_hi).
  const int i_lo = (m + kStep - 1) / kStep, i_hi = std::max(i_lo, (cw - m + kStep - 1) / kStep);
  constexpr int kChunk = 64;
  uint8_t pass[kChunk];
  for (int j = j_begin; j < j_end; ++j) {
    float* srow = score + static_cast<size_t>(j) * lw;
    uint8_t* orow = orientation + static_cast<size_t>(j) * lw;
    std::fill(srow, srow + lw, 0.0f);
    std::fill(orow, orow + lw, uint8_t{0});
    const int y = j * kStep;
    if (y < m || y >= ch - m) continue;
    for (int i0 = i_lo; i0 < i_hi; i0 += kChunk) {
      const int n = std::min(kChunk, i_hi - i0);
      gateRow(coarse, cw, w.gate_reach, levels.gate, i0, n, y, pass);
      for (int k = 0; k < n; ++k)
        if (pass[k]) cellScore(coarse, w, levels.floor, (i0 + k) * kStep, y, srow[i0 + k], orow[i0 + k]);
    }
  }
}

int findStreakPeakRows(const float* score, const uint8_t* mask, const StreakWindows& w, StreakPeak* out,
                       int count, int capacity, int j_begin, int j_end) {
  const int lw = w.lattice_width, lh = w.lattice_height;
  j_begin = std::max(j_begin, 1);
  j_end = std::min(j_end, lh - 1);
  for (int y = j_begin; y < j_end; ++y) {
    const float* row = score + static_cast<size_t>(y) * lw;
    for (int x = 1; x < lw - 1; ++x) {
      const float c = row[x];
      if (!(c > kStreakThreshold) || !mask[static_cast<size_t>(y) * lw + x]) continue;
      // Strict toward the top-left, non-strict toward the bottom-right: a
      // plateau gives one peak.
      bool peak = true;
      for (int dy = -1; dy <= 1 && peak; ++dy)
        for (int dx = -1; dx <= 1 && peak; ++dx) {
          if (!dx && !dy) continue;
          const float n = row[x + static_cast<ptrdiff_t>(dy) * lw + dx];
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

StreakFit streakFit(const float* coarse, const StreakWindows& w, const StreakPeak& p, int orientation) {
  StreakFit fit;
  Pair inner, s[4];
  const int px = p.x * kStreakLatticeStep, py = p.y * kStreakLatticeStep;  // coarse cell
  footprint(coarse, w, orientation, px, py, inner, s);
  fit.ba = 0.25f * (s[0].a + s[1].a + s[2].a + s[3].a);
  fit.bb = 0.25f * (s[0].b + s[1].b + s[2].b + s[3].b);
  const float da = inner.a - fit.ba, db = inner.b - fit.bb;
  const float d2 = da * da + db * db;
  const double f = w.factor;
  fit.cx = px * f + 0.5 * (f - 1), fit.cy = py * f + 0.5 * (f - 1);
  if (!(d2 > 0)) return fit;
  const double len = std::hypot(w.step_x[orientation], w.step_y[orientation]);
  fit.ux = w.step_x[orientation] / len, fit.uy = w.step_y[orientation] / len;
  fit.along = w.refine_along, fit.across = w.refine_across;
  fit.ka = da / d2, fit.kb = db / d2;
  fit.ok = true;
  return fit;
}

GridPx streakCentroid(const StreakFit& fit, const float* ca, const float* cb, int x0, int y0, int width, int height) {
  if (!fit.ok) return {fit.cx, fit.cy};
  const double reach = std::hypot(fit.along, fit.across);
  const int xa = std::max(x0, static_cast<int>(std::ceil(fit.cx - reach)));
  const int xb = std::min(x0 + width - 1, static_cast<int>(std::floor(fit.cx + reach)));
  const int ya = std::max(y0, static_cast<int>(std::ceil(fit.cy - reach)));
  const int yb = std::min(y0 + height - 1, static_cast<int>(std::floor(fit.cy + reach)));
  double sw = 0, sx = 0, sy = 0;
  for (int y = ya; y <= yb; ++y) {
    for (int x = xa; x <= xb; ++x) {
      const double ox = x - fit.cx, oy = y - fit.cy;
      const double along = ox * fit.ux + oy * fit.uy, across = -ox * fit.uy + oy * fit.ux;
      if (std::abs(along) > fit.along || std::abs(across) > fit.across) continue;
      const size_t k = static_cast<size_t>(y - y0) * width + (x - x0);
      const float proj = (ca[k] - fit.ba) * fit.ka + (cb[k] - fit.bb) * fit.kb - 0.25f;
      if (!(proj > 0)) continue;
      sw += proj, sx += proj * ox, sy += proj * oy;
    }
  }
  if (!(sw > 0)) return {fit.cx, fit.cy};
  return {fit.cx + sx / sw, fit.cy + sy / sw};
}

GridPx refineStreak(const float* ca, const float* cb, int width, int height, const float* coarse,
                    const StreakWindows& w, const StreakPeak& p, int orientation) {
  return streakCentroid(streakFit(coarse, w, p, orientation), ca, cb, 0, 0, width, height);
}

GridPx streakPeakCenter(const StreakWindows& w, const StreakPeak& p) {
  const double f = w.factor;
  const int px = p.x * kStreakLatticeStep, py = p.y * kStreakLatticeStep;
  return {px * f + 0.5 * (f - 1), py * f + 0.5 * (f - 1)};
}

bool nearBlob(const std::vector<Blob>& blobs, GridPx g, double grid_scale, double distance_mm) {
  const double near2 = std::pow(distance_mm / grid_scale, 2);
  for (const Blob& b : blobs) {
    const double dx = b.grid.x - g.x, dy = b.grid.y - g.y;
    if (dx * dx + dy * dy < near2) return true;
  }
  return false;
}

bool acceptStreakBlob(const std::vector<Blob>& blobs, const Blob& streak, double grid_scale,
                      const BlobColorGate& colors) {
  const double near2 = std::pow(kStreakBlobDistanceMm / grid_scale, 2);
  int streaks = 0;
  for (const Blob& b : blobs) {
    const double dx = b.grid.x - streak.grid.x, dy = b.grid.y - streak.grid.y;
    if (dx * dx + dy * dy < near2) return false;
    streaks += b.streak;
  }
  if (streaks >= kMaxStreakBlobs) return false;
  return colors.colored(streak.rgb);
}

}  // namespace dv

#include "pipeline/bayer_full.h"

#include <algorithm>

#include "pipeline/simd_clones.h"

namespace dv {

namespace {

// A site beyond the edge: the same color two pixels back.
inline int reflect(int c, int n) { return c < 0 ? c + 2 : (c >= n ? c - 2 : c); }

struct WindowRows {
  const uint8_t *r, *r_next, *b, *b_next, *g0, *g1;
  int g0_parity;  // column parity of the green site on the window's first row
};

// The rows that window row y reads. Rows are reflected like columns.
WindowRows windowRows(const cv::Mat& raw, BayerSites s, int y) {
  const int h = raw.rows;
  auto row = [&](int r) { return raw.ptr<uint8_t>(reflect(r, h)); };
  // Site row of a color inside rows y, y+1, and the next one of that color
  // on the far side of the window center.
  auto site = [&](int sy, const uint8_t*& at, const uint8_t*& next) {
    const int r = y + ((sy - y) & 1);
    at = row(r);
    next = row(r == y ? r + 2 : r - 2);
  };
  WindowRows w{};
  site(s.ry, w.r, w.r_next);
  site(s.by, w.b, w.b_next);
  w.g0 = row(y);
  w.g1 = row(y + 1);
  // On a red row the greens sit at the other column parity than red; on a
  // blue row at the other one than blue (which is red's).
  w.g0_parity = ((y - s.ry) & 1) == 0 ? 1 - s.rx : s.rx;
  return w;
}

// Window x of row set `w`, any x (columns reflected): r, g, b.
inline void windowAt(const WindowRows& w, BayerSites s, int width, int x, int& r, int& g, int& b) {
  auto color = [&](int sx, const uint8_t* at, const uint8_t* next) {
    const int c = x + ((sx - x) & 1);
    const int n = reflect(c == x ? c + 2 : c - 2, width);
    const int cc = reflect(c, width);
    return quarterShift(at[cc], at[n], next[cc], next[n]);
  };
  r = color(s.rx, w.r, w.r_next);
  b = color(s.bx, w.b, w.b_next);
  const int c0 = reflect(x + ((w.g0_parity - x) & 1), width);
  const int c1 = reflect(x + ((1 - w.g0_parity - x) & 1), width);
  g = (w.g0[c0] + w.g1[c1] + 1) >> 1;
}

// Interior windows 2i and 2i+1 for i in [i0, i1), every read in the image:
// offsets from 2i are constants for a red column parity RX and first-row
// green parity G0 (blue's column parity is 1 - RX in every pattern).
template <int RX, int G0>
DV_TEMPLATE_AVX2_CLONES void fullChromaPairs(
    const WindowRows& w, int i0, int i1, const ChromaFixed& k, uint32_t* out) {
  constexpr int BX = 1 - RX;
  // Site and next-site column offsets of the even (e) and odd (o) window.
  constexpr int re = RX, rne = RX == 0 ? 2 : -1, ro = RX == 1 ? 1 : 2, rno = RX == 1 ? 3 : 0;
  constexpr int be = BX, bne = BX == 0 ? 2 : -1, bo = BX == 1 ? 1 : 2, bno = BX == 1 ? 3 : 0;
  constexpr int g0e = G0, g0o = G0 == 1 ? 1 : 2, g1e = 1 - G0, g1o = G0 == 0 ? 1 : 2;
  const uint8_t *r = w.r, *rn = w.r_next, *b = w.b, *bn = w.b_next, *g0 = w.g0, *g1 = w.g1;
  const int ka0 = k.a[0], ka1 = k.a[1], ka2 = k.a[2], kb0 = k.b[0], kb1 = k.b[1], kb2 = k.b[2];
  auto pack = [&](int rr, int gg, int bb) {
    const int a = (ka0 * rr + ka1 * gg + ka2 * bb + 8) >> 4;
    const int c = (kb0 * rr + kb1 * gg + kb2 * bb + 8) >> 4;
    return (static_cast<uint32_t>(a) & 0xffffu) | (static_cast<uint32_t>(c) << 16);
  };
  for (int i = i0; i < i1; ++i) {
    const int x = 2 * i;
    const int r_e = (9 * r[x + re] + 3 * r[x + rne] + 3 * rn[x + re] + rn[x + rne] + 8) >> 4;
    const int b_e = (9 * b[x + be] + 3 * b[x + bne] + 3 * bn[x + be] + bn[x + bne] + 8) >> 4;
    const int g_e = (g0[x + g0e] + g1[x + g1e] + 1) >> 1;
    const int r_o = (9 * r[x + ro] + 3 * r[x + rno] + 3 * rn[x + ro] + rn[x + rno] + 8) >> 4;
    const int b_o = (9 * b[x + bo] + 3 * b[x + bno] + 3 * bn[x + bo] + bn[x + bno] + 8) >> 4;
    const int g_o = (g0[x + g0o] + g1[x + g1o] + 1) >> 1;
    out[x] = pack(r_e, g_e, b_e);
    out[x + 1] = pack(r_o, g_o, b_o);
  }
}

}  // namespace

void fullBayerChromaRows(const cv::Mat& raw, BayerPattern pattern, const ChromaFixed& k,
                         uint32_t* packed, int row_begin, int row_end, int col_begin, int col_end) {
  const BayerSites s = bayerSites(pattern);
  const int width = raw.cols;
  const int c0 = std::max(0, col_begin), c1 = col_end < 0 ? width : std::min(width, col_end);
  // Pairs (2i, 2i+1) inside [c0, c1) whose reads stay in the image
  // (columns 2i - 1 .. 2i + 3).
  const int i0 = std::max(1, (c0 + 1) / 2), i1 = std::max(i0, std::min(c1 / 2, (width - 2) / 2));
  for (int y = row_begin; y < row_end; ++y) {
    const WindowRows w = windowRows(raw, s, y);
    uint32_t* out = packed + static_cast<size_t>(width) * y;
    auto one = [&](int x) {
      int r, g, b;
      windowAt(w, s, width, x, r, g, b);
      out[x] = packChroma(k, r, g, b);
    };
    for (int x = c0; x < std::min(c1, 2 * i0); ++x) one(x);
    if (s.rx == 0) {
      if (w.g0_parity == 0) fullChromaPairs<0, 0>(w, i0, i1, k, out);
      else fullChromaPairs<0, 1>(w, i0, i1, k, out);
    } else {
      if (w.g0_parity == 0) fullChromaPairs<1, 0>(w, i0, i1, k, out);
      else fullChromaPairs<1, 1>(w, i0, i1, k, out);
    }
    for (int x = std::max(c0, 2 * i1); x < c1; ++x) one(x);
  }
}

void fullBayerRgbAt(const cv::Mat& raw, BayerPattern pattern, int x, int y, float rgb[3]) {
  const BayerSites s = bayerSites(pattern);
  x = std::clamp(x, 0, raw.cols - 1), y = std::clamp(y, 0, raw.rows - 1);
  int r, g, b;
  windowAt(windowRows(raw, s, y), s, raw.cols, x, r, g, b);
  rgb[0] = static_cast<float>(r), rgb[1] = static_cast<float>(g), rgb[2] = static_cast<float>(b);
}

}  // namespace dv

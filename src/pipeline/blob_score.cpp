#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "pipeline/kernels.h"
#include "pipeline/view_stretch.h"

namespace dv {

namespace {

// One score row from the table rows at y - r, y - q, y, y + q, y + r (any
// common per-column offset cancels: only differences are used).
__attribute__((target_clones("avx2", "default"))) void quadrantScoreRow(
    const uint32_t* s_top, const uint32_t* s_itop, const uint32_t* s_mid, const uint32_t* s_ibot,
    const uint32_t* s_bot, int width, int r, int q, float norm, float* out) {
  const int m = r + 1;
  for (int x = 0; x < m; ++x) out[x] = 0, out[width - 1 - x] = 0;
  // Box cell (x, y) sits at (x + 1/2, y + 1/2), so the quadrants of cell
  // (x, y) are box columns [x-r, x) and [x, x+r), rows [y-r, y) and [y, y+r).
  for (int x = m; x < width - m; ++x) {
    const uint32_t c = s_mid[x];
    // Full quadrant minus its inner q x q corner at the center.
    const int32_t tl = static_cast<int32_t>((c - s_top[x] - s_mid[x - r] + s_top[x - r]) -
                                            (c - s_itop[x] - s_mid[x - q] + s_itop[x - q]));
    const int32_t tr = static_cast<int32_t>((s_mid[x + r] - s_top[x + r] - c + s_top[x]) -
                                            (s_mid[x + q] - s_itop[x + q] - c + s_itop[x]));
    const int32_t bl = static_cast<int32_t>((s_bot[x] - c - s_bot[x - r] + s_mid[x - r]) -
                                            (s_ibot[x] - c - s_ibot[x - q] + s_mid[x - q]));
    const int32_t br = static_cast<int32_t>((s_bot[x + r] - s_mid[x + r] - s_bot[x] + c) -
                                            (s_ibot[x + q] - s_mid[x + q] - s_ibot[x] + c));
    const int32_t m1 = std::min(tl, br), m2 = std::min(-tr, -bl);
    out[x] = static_cast<float>(std::min(m1, m2)) * norm;
  }
}

inline float quadrantNorm(int r, int q) {
  // 4 G cells per table cell (2x2 box sums).
  return 1.0f / (4 * kGradientFixedPoint * (r * r - q * q));
}

}  // namespace

void quadrantMinScoreRows(const uint32_t* sat, int width, int height, int r, int q, float* score,
                          int y_begin, int y_end) {
  const size_t stride = static_cast<size_t>(width) + 1;
  const float norm = quadrantNorm(r, q);
  const int m = r + 1;
  for (int y = y_begin; y < y_end; ++y) {
    float* out = score + static_cast<size_t>(y) * width;
    if (y < m || y >= height - m || width <= 2 * m) {
      std::memset(out, 0, sizeof(float) * width);
      continue;
    }
    quadrantScoreRow(sat + (y - r) * stride, sat + (y - q) * stride, sat + y * stride, sat + (y + q) * stride,
                     sat + (y + r) * stride, width, r, q, norm, out);
  }
}

namespace {

// Rows of two whole planes.
class PlaneRows final : public ChromaRowSource {
 public:
  PlaneRows(const float* ca, const float* cb, int width) : ca_(ca), cb_(cb), w_(width) {}
  void rows(int y, const float*& a, const float*& b) override {
    a = ca_ + static_cast<size_t>(y) * w_;
    b = cb_ + static_cast<size_t>(y) * w_;
  }

 private:
  const float *ca_, *cb_;
  size_t w_;
};

// G row y from the source (zero where the gradient reaches past the plane).
void gradientRow(ChromaRowSource& src, int width, int height, double scale, int y, int32_t* out,
                 const GradientForms* forms) {
  const int k = static_cast<int>(std::floor(scale));
  const int m = k + 1;
  if (y < m || y >= height - m || width <= 2 * m) {
    std::memset(out, 0, sizeof(int32_t) * width);
    return;
  }
  // Highest row first: a source that makes rows as asked makes them all.
  const int ys[5] = {y + k + 1, y + k, y, y - k, y - k - 1};
  const float* a[5];
  const float* b[5];
  for (int i = 0; i < 5; ++i) src.rows(ys[i], a[4 - i], b[4 - i]);
  if (forms && !forms->plainRow(y)) gradientFormRowFrom(a, b, width, scale, forms->row(y), out);
  else gradientDotRowFrom(a, b, width, scale, out);
}

}  // namespace

void quadrantMinScoreFromChroma(const float* ca, const float* cb, int width, int height, double scale,
                                int r, int q, float* score, int y_begin, int y_end,
                                std::vector<uint32_t>& scratch, const GradientForms* forms) {
  PlaneRows rows(ca, cb, width);
  quadrantMinScoreFromRows(rows, width, height, scale, r, q, score, y_begin, y_end, scratch, forms);
}

void quadrantMinScoreFromRows(ChromaRowSource& src, int width, int height, double scale, int r, int q,
                              float* score, int y_begin, int y_end, std::vector<uint32_t>& scratch,
                              const GradientForms* forms, ScoreRowSink* sink) {
  const size_t stride = static_cast<size_t>(width) + 1;
  const float norm = quadrantNorm(r, q);
  const int m = r + 1;
  const int first = std::max(y_begin, m), last = std::min(y_end, height - m);  // rows with a score
  for (int y = y_begin; y < y_end; ++y)
    if (y < first || y >= last || width <= 2 * m) std::memset(score + static_cast<size_t>(y) * width, 0, sizeof(float) * width);
  if (first >= last || width <= 2 * m) return;
  // Column sums from table row t0 = first - r on (zero there), in a ring of
  // 2r + 1 rows: the band's own origin, so bands need nothing from each other.
  const int rows = 2 * r + 1;
  // Ring rows, two G rows (G shares the 32-bit scratch).
  scratch.resize(static_cast<size_t>(rows) * stride + 2 * static_cast<size_t>(width));  // no-op after the first frame
  auto ring = [&](int t) { return scratch.data() + static_cast<size_t>(t % rows) * stride; };
  int32_t* g_rows = reinterpret_cast<int32_t*>(scratch.data() + static_cast<size_t>(rows) * stride);
  auto g_row = [&](int y) { return g_rows + static_cast<size_t>(y & 1) * width; };
  const int t0 = first - r;
  std::memset(ring(t0), 0, sizeof(uint32_t) * stride);
  gradientRow(src, width, height, scale, t0, g_row(t0), forms);
  for (int t = t0 + 1; t <= last - 1 + r; ++t) {
    // Table row t: box row t - 1, i.e. G rows t - 1 and t (t < height - 1).
    gradientRow(src, width, height, scale, t, g_row(t), forms);
    boxRowPrefixOnto(g_row(t - 1), g_row(t), width, ring(t - 1), ring(t));
    const int y = t - r;  // all of rows y - r .. y + r are now in the ring
    if (y >= first) {
      quadrantScoreRow(ring(y - r), ring(y - q), ring(y), ring(y + q), ring(y + r), width, r, q, norm,
                       score + static_cast<size_t>(y) * width);
      if (sink) sink->rowDone(y);
    }
  }
}

__attribute__((target_clones("avx2", "default"))) void circleMinScoreRows(
    const uint32_t* row_prefix, int width, int height, double radius, float* score, int y_begin,
    int y_end) {
  const size_t stride = static_cast<size_t>(width) + 1;
  const int rows = std::max(1, static_cast<int>(std::floor(radius + 0.5)));
  // Half-widths of the quarter disc per row offset j = 1..rows: box cells at
  // distance (i - 1/2, j - 1/2) from the cell center, i, j >= 1.
  int half[64];
  int count = 0;
  const int nrows = std::min(rows, 63);
  for (int j = 1; j <= nrows; ++j) {
    const double dy = j - 0.5;
    half[j] = static_cast<int>(std::floor(std::sqrt(std::max(0.0, radius * radius - dy * dy)) + 0.5));
    count += half[j];
  }
  const float norm = 1.0f / (4 * kGradientFixedPoint * std::max(1, count));
  const int m = nrows + 1;
  for (int y = y_begin; y < y_end; ++y) {
    float* out = score + static_cast<size_t>(y) * width;
    if (y < m || y >= height - m || width <= 2 * m) {
      std::memset(out, 0, sizeof(float) * width);
      continue;
    }
    for (int x = 0; x < m; ++x) out[x] = 0, out[width - 1 - x] = 0;
    for (int x = m; x < width - m; ++x) {
      uint32_t tl = 0, tr = 0, bl = 0, br = 0;
      for (int j = 1; j <= nrows; ++j) {
        const int h = half[j];
        if (h == 0) continue;
        const uint32_t* up = row_prefix + (y - j + 1) * stride;  // box row y-j
        const uint32_t* dn = row_prefix + (y + j) * stride;      // box row y+j-1
        tl += up[x] - up[x - h];
        tr += up[x + h] - up[x];
        bl += dn[x] - dn[x - h];
        br += dn[x + h] - dn[x];
      }
      const int32_t m1 = std::min(static_cast<int32_t>(tl), static_cast<int32_t>(br));
      const int32_t m2 = std::min(-static_cast<int32_t>(tr), -static_cast<int32_t>(bl));
      out[x] = static_cast<float>(std::min(m1, m2)) * norm;
    }
  }
}

}  // namespace dv

// The banded pass (band_plan.h): Bayer subsampling, rectification, score
// and peaks band by band, each band's rows in cache from mosaic to peaks.
#include "pipeline/cpu_pipeline_impl.h"

namespace dv {

using cpu_pipeline_detail::msSince;

class CpuPipeline::Impl::BandRows final : public ChromaRowSource {
 public:
  BandRows(Impl& m, const BandPlan::Band& band, const uint32_t* box, float gain, float* halo_a,
           float* halo_b)
      : m_(m), band_(band), box_(box), gain_(gain), halo_a_(halo_a), halo_b_(halo_b), done_(band.lo) {}
  void rows(int y, const float*& a, const float*& b) override {
    if (y >= done_) makeUpTo(y + 1);
    float *pa, *pb;
    rowPointers(y, pa, pb);
    a = pa, b = pb;
  }
  void makeUpTo(int y_end) {
    const size_t w = static_cast<size_t>(m_.grid.width);
    const RemapTable& t = m_.readTable();
    for (; done_ < y_end; ++done_) {
      float *a, *b;
      rowPointers(done_, a, b);
      rectifyChromaCells(m_.bands.index.data() + band_.index_offset + (done_ - band_.lo) * w,
                         t.frac.data() + done_ * w, band_.stride, box_, gain_, a, b, w);
      // The fast-ball pass's coarse row that reads this own row, while it
      // is in cache (each own row belongs to one band, so each is made once).
      const int f = m_.streak.factor, c = done_ / f;
      if (done_ % f == 0 && done_ >= band_.y_begin && done_ < band_.y_end && c < m_.streak.coarse_height)
        streakCoarseRows(m_.ca.data(), m_.cb.data(), m_.grid.width, m_.streak, m_.streak_coarse.data(), c,
                         c + 1);
    }
  }

 private:
  void rowPointers(int y, float*& a, float*& b) const {
    const size_t w = static_cast<size_t>(m_.grid.width);
    if (y >= band_.y_begin && y < band_.y_end) {
      a = m_.ca.data() + y * w;
      b = m_.cb.data() + y * w;
      return;
    }
    const size_t slot = y < band_.y_begin ? y - band_.lo : (band_.y_begin - band_.lo) + (y - band_.y_end);
    a = halo_a_ + slot * w;
    b = halo_b_ + slot * w;
  }
  Impl& m_;
  const BandPlan::Band& band_;
  const uint32_t* box_;
  float gain_;
  float *halo_a_, *halo_b_;
  int done_;
};

class CpuPipeline::Impl::BandPeakRows final : public ScoreRowSink {
 public:
  BandPeakRows(Impl& m, const BandPlan::Band& band, BandPeaks& out)
      : m_(m), band_(band), out_(out), low_(m.lowThreshold() * kEnergyFloor), raw_(m.rawThreshold()),
        threshold_(static_cast<float>(m.opt.threshold)), reach_(m.energyReach()) {}
  void rowDone(int y) override {
    const int t = y - 1;
    if (t <= band_.y_begin) return;  // the first row is left for after the pass
    BandPeaks::List& l = out_.inner;
    const int from = out_.scanRow(l, m_.score.data(), m_.peak_mask.data(), m_.grid.width, m_.grid.height,
                                  m_.margin, low_, t);
    if (t - reach_ < band_.y_begin || t + reach_ >= band_.y_end) return;
    for (int i = from; i < l.n; ++i)
      if (l.peaks[i].score > raw_) l.ratio[i] = m_.peakRatio(l.peaks[i], threshold_);
  }

 private:
  Impl& m_;
  const BandPlan::Band& band_;
  BandPeaks& out_;
  float low_, raw_, threshold_;
  int reach_;
};

void CpuPipeline::Impl::finishBandPeaks(int c) {
  const BandPlan::Band& band = bands.bands[c];
  BandPeaks& bp = band_peaks[c];
  const float low = lowThreshold() * kEnergyFloor, raw = rawThreshold();
  const float threshold = static_cast<float>(opt.threshold);
  if (band.y_end == band.y_begin) return;  // an empty band (a grid of few rows)
  bp.scanRow(bp.first, score.data(), peak_mask.data(), grid.width, grid.height, margin, low, band.y_begin);
  if (band.y_end - 1 > band.y_begin)
    bp.scanRow(bp.last, score.data(), peak_mask.data(), grid.width, grid.height, margin, low, band.y_end - 1);
  for (BandPeaks::List* l : {&bp.first, &bp.inner, &bp.last})
    for (int i = 0; i < l->n; ++i) {
      const PeakCandidate& c = l->peaks[i];
      if (!(c.score > raw)) continue;
      if (l->ratio[i] == BandPeaks::kRatioPending) l->ratio[i] = peakRatio(c, threshold);
      if (!(l->ratio[i] > threshold)) continue;
      if (bp.blob_n == static_cast<int>(bp.blobs.size())) {
        bp.full = true;
        return;
      }
      bp.blob_cells[bp.blob_n] = {c.x, c.y, l->ratio[i]};
      bp.blobs[bp.blob_n++] = peakBlob(c.x, c.y, l->ratio[i]);
    }
}

Blob CpuPipeline::Impl::peakBlob(int x, int y, float ratio) const {
  Blob blob;
  blob.grid = interpolatePeak(score.data(), grid.width, x, y);
  blob.position = grid.toField(blob.grid);
  blob.score = ratio;
  meanColor(blob.grid, blob.rgb);
  return blob;
}

void CpuPipeline::Impl::bandWeakPeaks(int c, float low) {
  BandPeaks& bp = band_peaks[c];
  const float raw_low = low * kEnergyFloor, threshold = static_cast<float>(opt.threshold);
  for (const BandPeaks::List* l : {&bp.first, &bp.inner, &bp.last})
    for (int i = 0; i < l->n; ++i) {
      const PeakCandidate& p = l->peaks[i];
      if (!(p.score > raw_low) || !reach.nearKept(p.x, p.y)) continue;
      ++bp.weak_raw;
      const float ratio = peakRatio(p, low);
      if (!(ratio > low && ratio <= threshold)) continue;
      if (bp.weak_n == static_cast<int>(bp.weak.size())) {
        bp.full = true;
        return;
      }
      bp.weak_cells[bp.weak_n] = {p.x, p.y, ratio};
      bp.weak[bp.weak_n++] = peakBlob(p.x, p.y, ratio);
    }
}

void CpuPipeline::Impl::bandedScore(const cv::Mat& raw, float gain) {
  const int gw = grid.width, gh = grid.height;
  pool.parallelFor(static_cast<int>(bands.bands.size()), [&](int first, int last) {
    // Per thread, sized on the first frame.
    thread_local std::vector<uint32_t> box_store, ring;
    thread_local std::vector<float> halo;
    box_store.resize(bands.box_size + 16);
    halo.resize(2 * static_cast<size_t>(bands.haloRows()) * gw);
    // Whole 64-byte lines for the box rows (its stride is a multiple of 16).
    uint32_t* box = box_store.data();
    while (reinterpret_cast<uintptr_t>(box) % 64) ++box;
    for (int c = first; c < last; ++c) {
      const BandPlan::Band& band = bands.bands[c];
      const auto t0 = std::chrono::steady_clock::now();
      bayerChromaBox(raw, opt.bayer, chroma_fixed, transposed, box, band.stride, band.i_begin, band.i_end,
                     band.j_begin, band.j_end);
      band_bayer_ms[c] = msSince(t0);
      BandRows rows(*this, band, box, gain, halo.data(), halo.data() + static_cast<size_t>(bands.haloRows()) * gw);
      band_peaks[c].clear();
      BandPeakRows peaks(*this, band, band_peaks[c]);
      quadrantMinScoreFromRows(rows, gw, gh, gradient_scale, quadrant_r, inner_q, score.data(), band.y_begin,
                               band.y_end, ring, &forms, &peaks);
      rows.makeUpTo(band.y_end);  // own rows the score did not need (next to the plane's edges)
    }
  });
}

}  // namespace dv

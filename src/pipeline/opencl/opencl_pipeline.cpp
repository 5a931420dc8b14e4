#include "pipeline/opencl/opencl_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "pipeline/bayer_sampling.h"
#include "pipeline/bayer_subsample.h"
#include "pipeline/kernels.h"
#include "pipeline/remap_table.h"
#include "pipeline/score_windows.h"
#include "pipeline/view_stretch.h"
#include "pipeline/streak_score.h"
#include "pipeline/thread_pool.h"

namespace dv {


OpenClPipeline::OpenClPipeline(const CameraModel& camera, const FieldModel& field,
                               const PipelineOptions& opt, const OclDeviceInfo& device)
    : camera_(camera), opt_(opt), color_gate_(camera, field) {
  const auto& c = camera_.calibration();
  const int image_w = static_cast<int>(c.image_width), image_h = static_cast<int>(c.image_height);
  const BayerSamplingChoice sampling = chooseBayerSampling(camera_, field, opt_);
  opt_.bayer_sampling = sampling.mode;
  sampling_note_ = sampling.describe();
  grid_ = checkedGrid(camera_, field, opt_);
  const SampleLattice lattice = sampleLattice(opt_);

  OclEngineConfig cfg;
  cfg.image_width = image_w;
  cfg.image_height = image_h;
  cfg.bayer = opt_.bayer != BayerPattern::None;
  cfg.full_bayer = cfg.bayer && opt_.bayer_sampling == BayerSampling::Full;
  const BayerSites sites = bayerSites(opt_.bayer);
  cfg.red_x = sites.rx, cfg.red_y = sites.ry, cfg.blue_x = sites.bx, cfg.blue_y = sites.by;
  cfg.grid_width = grid_.width;
  cfg.grid_height = grid_.height;

  const ScoreWindows w = scoreWindows(grid_.scale, opt_.score);
  cfg.gradient_scale = w.gradient_scale;
  cfg.quadrant_radius = w.quadrant_radius;
  cfg.circle_radius = w.circle_radius;
  cfg.inner_corner = w.inner_corner;
  cfg.circle_score = opt_.score == BlobScoreKind::CircleMin;
  cfg.margin = w.margin;
  cfg.energy_window = w.energy_window;
  cfg.energy_floor = kEnergyFloor;
  cfg.color_radius = w.color_radius;
  cfg.threshold = static_cast<float>(opt_.threshold);
  cfg.max_blobs = opt_.max_blobs;
  cfg.weak_threshold = static_cast<float>(opt_.weak_threshold);
  cfg.max_weak_blobs = opt_.max_weak_blobs;
  const ChromaTransform chroma = ChromaTransform::of(opt_.color);
  color_gate_.setChroma(chroma);
  for (int i = 0; i < 3; ++i) {  // as CpuPipeline's ChromaFixed
    cfg.chroma_a[i] = static_cast<int>(std::lround(chroma.a[i] * 1024));
    cfg.chroma_b[i] = static_cast<int>(std::lround(chroma.b[i] * 1024));
  }

  // The remap table through the CPU reference's own builder.
  {
    ThreadPool pool(opt_.threads);
    RemapTable table;
    table.build(camera_, grid_, opt_.plane_height, lattice, pool);
    cfg.region_x_begin = table.x_begin, cfg.region_x_end = table.x_end;
    cfg.region_y_begin = table.y_begin, cfg.region_y_end = table.y_end;
    cfg.remap_index = std::move(table.index);
    cfg.remap_frac = std::move(table.frac);
    cfg.peak_mask = peakMask(table.valid, grid_.width, grid_.height, w);  // as the CPU reference
    const GradientForms forms = gradientForms(camera_, grid_, opt_.plane_height);
    if (forms.any) {
      cfg.form_block = kFormBlock;
      cfg.form_blocks_x = forms.blocks_x;
      cfg.gradient_forms = forms.coef;
      cfg.form_plain = forms.plain;
      cfg.form_plain_row = forms.plain_row;
    }
    streak_ = streakWindows(grid_.scale, grid_.width, grid_.height);
    applyStreakWindows(streak_, streakPeakMask(table.valid.data(), grid_.width, grid_.height, streak_), cfg);
    streak_markings_ = MarkingMask(camera, field, grid_, opt_.plane_height);
    streak_later_.reserve(kMaxStreakCandidates);
  }
  engine_ = std::make_unique<OclEngine>(std::make_shared<OclContext>(device), std::move(cfg));
  const auto& ec = engine_->config();
  spacing_.configure(ec.grid_width, ec.grid_height, kMinBlobDistanceMm / grid_.scale,
                     std::max(0, ec.max_blobs) + std::max(0, ec.max_weak_blobs));
  reach_.configure(ec.grid_width, ec.grid_height, w.weak_reach, std::max(0, ec.max_blobs) + ExpectedPlaces::kMax);
}

OpenClPipeline::~OpenClPipeline() = default;

std::string OpenClPipeline::name() const { return "opencl " + engine_->context().device().device_name; }

std::optional<ImagePx> OpenClPipeline::gridToImage(GridPx g) const {
  const FieldMm f = grid_.toField(g);
  return camera_.fieldToImage({f.x, f.y, opt_.plane_height});
}

bool OpenClPipeline::process(const cv::Mat& raw, BlobList& out) {
  out.clear();
  out.plane_height = opt_.plane_height;
  const auto& cfg = engine_->config();
  // The same checks and messages as the CPU reference.
  if (raw.empty()) {
    error_ = "empty frame";
    return false;
  }
  if (raw.cols != cfg.image_width || raw.rows != cfg.image_height) {
    error_ = "frame is " + std::to_string(raw.cols) + "x" + std::to_string(raw.rows) +
             ", calibration expects " + std::to_string(cfg.image_width) + "x" + std::to_string(cfg.image_height);
    return false;
  }
  if (raw.depth() != CV_8U || (raw.channels() != 1 && raw.channels() != 3)) {
    error_ = "frame type must be 8-bit Bayer (1 channel) or 8-bit BGR (3 channels)";
    return false;
  }
  if (raw.channels() == 1 && opt_.bayer == BayerPattern::None) {
    error_ = "1-channel frame but the Bayer pattern is 'none'";
    return false;
  }
  const bool bayer = raw.channels() == 1;
  if (bayer != cfg.bayer) {
    error_ = bayer ? "Bayer frame for a BGR camera" : "BGR frame for a camera configured as Bayer";
    return false;
  }
  error_.clear();
  const auto t0 = std::chrono::steady_clock::now();
  uint8_t* dst = engine_->frameBuffer();
  if (!dst) {
    error_ = engine_->error();
    return false;
  }
  const size_t row_bytes = static_cast<size_t>(engine_->frameStride());
  if (raw.isContinuous()) {
    std::memcpy(dst, raw.data, row_bytes * raw.rows);
  } else {
    for (int y = 0; y < raw.rows; ++y) std::memcpy(dst + row_bytes * y, raw.ptr(y), row_bytes);
  }
  if (!engine_->runPeaks()) {
    error_ = engine_->error();
    return false;
  }
  // As the CPU reference: strongest first, a weaker peak within
  // kMinBlobDistanceMm of a kept blob is the same blob, near-neutral colors
  // are line crossings or gray features. The engine lists the peaks above
  // the threshold first, then the weak ones, of which those within the weak
  // reach of a blob count, up to max_weak_blobs.
  spacing_.clear();
  reach_.clear();
  for (int k = 0; k < expected_.n; ++k) {
    const GridPx g = grid_.toGrid(expected_.at[k]);
    reach_.keep(g.x, g.y);
  }
  color_gate_.measureNeutral(raw, opt_.bayer);
  color_gate_.beginPeaks();
  for (const auto& p : engine_->peaks()) {
    if (!(p.score > cfg.threshold)) break;  // the strong ones come first
    const float rgb[3] = {p.r, p.g, p.b};
    color_gate_.addPeak(rgb);
  }
  color_gate_.endPeaks();
  out.neutral = color_gate_.neutral();
  out.carpet = color_gate_.carpet();
  out.min_saturation = color_gate_.threshold();
  // The fast-ball pass weighs streaks against this frame's marker contrast.
  if (!engine_->runStreaks(streakLevels(color_gate_.markerContrast(), engine_->lastLumaMean()))) {
    error_ = engine_->error();
    return false;
  }
  for (const auto& p : engine_->peaks()) {
    const bool weak = !(p.score > cfg.threshold);
    if (weak && (static_cast<int>(out.weak.size()) >= cfg.max_weak_blobs || !reach_.nearKept(p.cell_x, p.cell_y)))
      continue;
    if (spacing_.nearKept(p.cell_x, p.cell_y)) continue;
    Blob b;
    b.grid = {p.x, p.y};
    b.position = grid_.toField(b.grid);
    b.score = p.score;
    b.rgb[0] = p.r, b.rgb[1] = p.g, b.rgb[2] = p.b;
    if (!color_gate_.colored(b.rgb)) {
      if (!weak) out.keepIfPale(b);
      continue;
    }
    spacing_.keep(b.grid.x, b.grid.y);
    if (weak) {
      out.weak.push_back(b);
    } else {
      out.blobs.push_back(b);
      reach_.keep(b.grid.x, b.grid.y);
    }
  }
  // Fast-ball streaks, as the CPU reference (streak_score.h).
  takeStreaksMarkingsLast(
      engine_->streakPeaks(),
      [&](const OclPeak& p, Blob& b) {
        const StreakPeak cell{static_cast<int>(p.cell_x), static_cast<int>(p.cell_y), p.score};
        if (nearBlob(out.blobs, streakPeakCenter(streak_, cell), grid_.scale)) return false;
        b.grid = {p.x, p.y};
        b.position = grid_.toField(b.grid);
        b.score = p.score;
        b.streak = true;
        b.rgb[0] = p.r, b.rgb[1] = p.g, b.rgb[2] = p.b;
        return true;
      },
      streak_markings_, raw, opt_.bayer, engine_->lastStreakLevels(), out.blobs, streak_later_, grid_.scale, color_gate_);
  const auto& t = engine_->times();
  times_.bayer_ms = t.bayer_ms;
  times_.rectify_ms = t.rectify_ms;  // fused with the chroma transform
  times_.color_ms = 0;
  times_.gradient_ms = t.gradient_ms;
  times_.sat_ms = t.sat_ms;
  times_.score_ms = t.score_ms;
  times_.peaks_ms = t.peaks_ms + t.download_ms;
  times_.streak_ms = t.streak_ms;
  times_.total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

}  // namespace dv

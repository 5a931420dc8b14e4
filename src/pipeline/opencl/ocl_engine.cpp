#include "pipeline/opencl/ocl_engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace dv {

namespace {

constexpr float kGradientFixedPoint = 16384.0f;  // as pipeline/kernels.h
constexpr int kHeaderWords = 4;                  // DV_RESULT_HEADER in common.cl
constexpr int kPeakWords = 8;                    // floats per OclPeak
constexpr int kFirstPeaksRead = 256;             // peaks read with the counters
constexpr float kPackedChromaScale = 64.0f;      // as pipeline/bayer_subsample.h

static_assert(sizeof(OclPeak) == kPeakWords * sizeof(float), "OclPeak must match dv_peak");

size_t roundUp(size_t n, size_t m) { return (n + m - 1) / m * m; }

// Largest power of two <= n (n >= 1).
size_t floorPow2(size_t n) {
  size_t p = 1;
  while (p * 2 <= n) p *= 2;
  return p;
}

double eventMs(cl_event start, cl_event end) {
  cl_ulong t0 = 0, t1 = 0;
  if (!start || !end) return 0;
  clGetEventProfilingInfo(start, CL_PROFILING_COMMAND_START, sizeof t0, &t0, nullptr);
  clGetEventProfilingInfo(end, CL_PROFILING_COMMAND_END, sizeof t1, &t1, nullptr);
  return t1 > t0 ? (t1 - t0) * 1e-6 : 0.0;
}

}  // namespace

// Device objects; released in reverse order of creation.
struct OclEngine::Buffers {
  cl_mem input_host = nullptr;  // CL_MEM_ALLOC_HOST_PTR: pinned / shared frame memory
  cl_mem input_dev = nullptr;   // discrete devices only
  cl_mem packed = nullptr, remap_index = nullptr, remap_frac = nullptr, mask = nullptr;
  cl_mem chroma = nullptr, gdot = nullptr, sat = nullptr, score = nullptr;
  cl_mem forms = nullptr, form_plain = nullptr, form_plain_row = nullptr;
  cl_mem results = nullptr, results_host = nullptr, half = nullptr;
  cl_mem streak_coarse = nullptr, streak_score = nullptr, streak_orient = nullptr, streak_mask = nullptr,
         streak_shape = nullptr, streak_list = nullptr;
  uint32_t* results_mapped = nullptr;  // pinned host copy of the results header + peaks

  cl_kernel subsample = nullptr, rectify = nullptr, gradient = nullptr, sat_rows = nullptr,
            sat_cols = nullptr, score_k = nullptr, peaks = nullptr, streak_coarse_k = nullptr,
            streak_score_k = nullptr, streak_peaks_k = nullptr;
  size_t subsample_local[2] = {16, 16}, pixel_local[2] = {32, 8};
  size_t sat_rows_local = 256, sat_cols_local[2] = {32, 8};

  // Events of the last frame: upload, subsample, rectify, gradient, sat rows,
  // sat columns, score, peaks, download (+ second download).
  enum { kUpload, kSubsample, kRectify, kGradient, kSatRows, kSatCols, kScore, kPeaks, kStreakCoarse,
         kStreakScore, kStreakPeaks, kDownload, kDownload2, kStreakDownload, kEvents };
  cl_event events[kEvents] = {};

  void releaseEvents() {
    for (auto& e : events)
      if (e) clReleaseEvent(e), e = nullptr;
  }

  ~Buffers() {
    releaseEvents();
    for (cl_kernel k : {subsample, rectify, gradient, sat_rows, sat_cols, score_k, peaks, streak_coarse_k,
                        streak_score_k, streak_peaks_k})
      if (k) clReleaseKernel(k);
    for (cl_mem m : {input_host, input_dev, packed, remap_index, remap_frac, mask, chroma, gdot, sat,
                     score, results, results_host, half, streak_coarse, streak_score, streak_orient,
                     streak_mask, streak_shape, streak_list, forms, form_plain, form_plain_row})
      if (m) clReleaseMemObject(m);
  }
};

void applyStreakWindows(const StreakWindows& w, std::vector<uint8_t> mask, OclEngineConfig& c) {
  c.streak_mask = std::move(mask);
  c.streak_factor = w.factor;
  c.streak_coarse_width = w.coarse_width;
  c.streak_coarse_height = w.coarse_height;
  c.streak_lattice_width = w.lattice_width;
  c.streak_lattice_height = w.lattice_height;
  c.streak_margin = w.margin;
  for (int o = 0; o < kStreakOrientations; ++o) {
    c.streak_step_x[o] = w.step_x[o];
    c.streak_step_y[o] = w.step_y[o];
    c.streak_inner[o] = w.inner[o];
    c.streak_side[o] = w.side[o];
    c.streak_end[o] = w.end[o];
  }
  c.streak_refine_along = static_cast<float>(w.refine_along);
  c.streak_refine_across = static_cast<float>(w.refine_across);
  c.streak_threshold = kStreakThreshold;
  c.streak_floor = kStreakFloor;
  c.streak_gate_reach = w.gate_reach;
  c.streak_gate = kStreakGate;
  c.streak_capacity = kMaxStreakCandidates;
}

OclEngine::OclEngine(std::shared_ptr<OclContext> ctx, OclEngineConfig config)
    : ctx_(std::move(ctx)), cfg_(std::move(config)), b_(std::make_unique<Buffers>()) {
  const auto& c = cfg_;
  if (c.image_width < 4 || c.image_height < 4)
    throw std::invalid_argument("OpenCL pipeline: image size too small");
  if (c.bayer && (c.image_width % 2 || c.image_height % 2))
    throw std::invalid_argument("OpenCL pipeline: Bayer image size must be even");
  const bool subsampled = c.bayer && !c.full_bayer;
  src_width_ = subsampled ? c.image_width / 2 : c.image_width;
  src_height_ = subsampled ? c.image_height / 2 : c.image_height;
  const size_t cells = static_cast<size_t>(c.grid_width) * c.grid_height;
  if (c.grid_width < 8 || c.grid_height < 8 || c.remap_index.size() != cells ||
      c.remap_frac.size() != cells || c.peak_mask.size() != cells)
    throw std::invalid_argument("OpenCL pipeline: grid tables do not match the grid size");
  // Every bilinear footprint must lie inside the RGBX image: the kernels do
  // not bounds-check their four reads.
  const int64_t last = static_cast<int64_t>(src_width_) * src_height_ - src_width_ - 1;
  for (int32_t i : c.remap_index)
    if (i < 0 || i >= last) throw std::invalid_argument("OpenCL pipeline: remap index out of range");
  const int window = c.circle_score ? std::max(1, static_cast<int>(std::floor(c.circle_radius + 0.5)))
                                    : c.quadrant_radius;
  const int reach = static_cast<int>(std::floor(c.gradient_scale)) + 1;
  const size_t coarse_cells = static_cast<size_t>(c.streak_coarse_width) * c.streak_coarse_height;
  const size_t lattice_cells = static_cast<size_t>(c.streak_lattice_width) * c.streak_lattice_height;
  // OpenCL has no empty buffers: a grid too small for the footprint is refused here.
  if (c.streak_factor < 1 || lattice_cells == 0 || c.streak_coarse_width * c.streak_factor > c.grid_width ||
      c.streak_coarse_height * c.streak_factor > c.grid_height || c.streak_mask.size() != lattice_cells ||
      c.streak_lattice_width != (c.streak_coarse_width + 1) / 2 ||
      c.streak_lattice_height != (c.streak_coarse_height + 1) / 2 ||
      c.streak_capacity < 1)
    throw std::invalid_argument("OpenCL pipeline: streak tables do not match the grid");
  for (int o = 0; o < 4; ++o)
    if (std::max(c.streak_side[o], c.streak_end[o]) * std::max(std::abs(c.streak_step_x[o]),
                                                               std::abs(c.streak_step_y[o])) >= c.streak_margin)
      throw std::invalid_argument("OpenCL pipeline: streak margin smaller than its footprint");
  if (c.streak_gate_reach < 1 || c.streak_gate_reach >= c.streak_margin)
    throw std::invalid_argument("OpenCL pipeline: streak margin smaller than its gate");
  if (c.quadrant_radius < 1 || c.inner_corner < 0 || c.inner_corner >= c.quadrant_radius ||
      c.margin < std::max(window, c.energy_window) + reach)
    throw std::invalid_argument("OpenCL pipeline: margin smaller than the score window");

  frame_stride_ = c.bayer ? c.image_width : 3 * c.image_width;
  frame_bytes_ = static_cast<size_t>(frame_stride_) * c.image_height;
  const auto& dev = ctx_->device();
  zero_copy_ = dev.host_unified_memory;
  fp64_ = ctx_->fp64();
  capacity_ = std::max({1024, 4 * (c.max_blobs + weakCapacity()), 16});
  const int ws = src_width_, hs = src_height_;
  // Where the brightness is measured: samples, or the 2x2 cells under full
  // samples (as fullBayerCells in pipeline/bayer_full.h).
  cl_int4 region = {{c.region_x_begin, c.region_x_end, c.region_y_begin, c.region_y_end}};
  if (c.full_bayer)
    region = {{c.region_x_begin / 2, (c.region_x_end + 1) / 2, c.region_y_begin / 2, (c.region_y_end + 1) / 2}};
  {
    // Samples of the brightness sum, as the CPU reference counts them.
    const int rows = std::max(0, region.s[3] - region.s[2]);
    const int cols = std::max(0, region.s[1] - region.s[0]);
    const double n = (c.bayer ? 6.0 : 3.0) * ((rows + 15) / 16) * ((cols + 3) / 4);
    luma_count_ = static_cast<float>(std::max(1.0, n));
  }
  peaks_.reserve(capacity_);
  streak_peaks_.reserve(c.streak_capacity);
  streak_host_.assign(kHeaderWords + static_cast<size_t>(c.streak_capacity) * kPeakWords, 0);

  cl_context cx = ctx_->context();
  cl_int st = CL_SUCCESS;
  auto make = [&](cl_mem_flags flags, size_t bytes, const void* host, const char* what) {
    cl_mem m = clCreateBuffer(cx, flags, std::max<size_t>(bytes, 4), const_cast<void*>(host), &st);
    if (st != CL_SUCCESS)
      throw OclError(std::string("cannot allocate the ") + what + " buffer (" +
                         std::to_string(bytes >> 10) + " KiB) on " + dev.device_name,
                     st);
    return m;
  };
  const cl_mem_flags input_flags = (c.pinned_input ? CL_MEM_ALLOC_HOST_PTR : 0) | CL_MEM_READ_ONLY;
  if (!c.pinned_input) zero_copy_ = false;
  b_->input_host = make(input_flags, frame_bytes_, nullptr, "frame");
  if (!zero_copy_) b_->input_dev = make(CL_MEM_READ_ONLY, frame_bytes_, nullptr, "device frame");
  b_->packed = make(CL_MEM_READ_WRITE, 4ull * ws * hs, nullptr, "packed chroma");
  b_->remap_index = make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, cells * 4, c.remap_index.data(), "remap");
  b_->remap_frac = make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, cells * 2, c.remap_frac.data(), "remap");
  b_->mask = make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, cells, c.peak_mask.data(), "peak mask");
  b_->chroma = make(CL_MEM_READ_WRITE, cells * 8, nullptr, "chroma");  // float pairs
  b_->gdot = make(CL_MEM_READ_WRITE, cells * 4, nullptr, "gradient");
  {
    // One dummy element where the view is plain everywhere (buffers may not be empty).
    const bool use = !c.gradient_forms.empty() && !c.circle_score;
    std::vector<float> f = use ? c.gradient_forms : std::vector<float>(6, 0.f);
    std::vector<uint8_t> p = use ? c.form_plain : std::vector<uint8_t>(1, 1);
    std::vector<uint8_t> pr = use ? c.form_plain_row : std::vector<uint8_t>(1, 1);
    b_->forms = make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, f.size() * 4, f.data(), "gradient forms");
    b_->form_plain = make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, p.size(), p.data(), "gradient forms");
    b_->form_plain_row = make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, pr.size(), pr.data(), "gradient forms");
  }
  const size_t sat_words = static_cast<size_t>(c.grid_width + 1) * (c.grid_height + 1);
  {
    std::vector<uint32_t> zeros(sat_words, 0);  // row 0 of the table stays 0
    b_->sat = make(CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sat_words * 4, zeros.data(), "summed-area");
  }
  b_->score = make(CL_MEM_READ_WRITE, cells * 4, nullptr, "score");
  const size_t result_bytes = (kHeaderWords + static_cast<size_t>(capacity_) * kPeakWords) * 4;
  {
    std::vector<uint32_t> zeros(result_bytes / 4, 0);
    b_->results = make(CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, result_bytes, zeros.data(), "peak list");
  }
  b_->results_host = make(CL_MEM_ALLOC_HOST_PTR | CL_MEM_WRITE_ONLY, result_bytes, nullptr, "peak list");
  int half[64] = {0};
  float circle_norm = 1;
  int circle_rows = 1;
  {
    // As circleMinScoreRows: box cells at (i - 1/2, j - 1/2) from the center.
    const int rows = std::max(1, static_cast<int>(std::floor(c.circle_radius + 0.5)));
    circle_rows = std::min(rows, 63);
    int count = 0;
    for (int j = 1; j <= circle_rows; ++j) {
      const double dy = j - 0.5;
      half[j] = static_cast<int>(
          std::floor(std::sqrt(std::max(0.0, c.circle_radius * c.circle_radius - dy * dy)) + 0.5));
      count += half[j];
    }
    circle_norm = 1.0f / (4 * kGradientFixedPoint * std::max(1, count));
  }
  b_->half = make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof half, half, "circle");
  b_->streak_coarse = make(CL_MEM_READ_WRITE, coarse_cells * 8, nullptr, "streak chroma");
  b_->streak_score = make(CL_MEM_READ_WRITE, lattice_cells * 4, nullptr, "streak score");
  b_->streak_orient = make(CL_MEM_READ_WRITE, lattice_cells, nullptr, "streak orientation");
  b_->streak_mask = make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, lattice_cells, c.streak_mask.data(),
                         "streak mask");
  {
    // dv_streak_shape in streak.cl: five arrays of four ints.
    cl_int shape[20];
    for (int o = 0; o < 4; ++o) {
      shape[o] = c.streak_step_x[o];
      shape[4 + o] = c.streak_step_y[o];
      shape[8 + o] = c.streak_inner[o];
      shape[12 + o] = c.streak_side[o];
      shape[16 + o] = c.streak_end[o];
    }
    b_->streak_shape = make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof shape, shape, "streak shape");
  }
  b_->streak_list = make(CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, streak_host_.size() * 4,
                         streak_host_.data(), "streak list");

  cl_command_queue q = ctx_->queue();
  // Pinned host memory stays mapped for the engine's life where it is a DMA
  // staging area; on shared-memory devices it is mapped per frame instead.
  if (!zero_copy_) {
    mapped_ = static_cast<uint8_t*>(
        clEnqueueMapBuffer(q, b_->input_host, CL_TRUE, CL_MAP_WRITE, 0, frame_bytes_, 0, nullptr, nullptr, &st));
    if (st != CL_SUCCESS) throw OclError("cannot map the pinned frame buffer", st);
  }
  b_->results_mapped = static_cast<uint32_t*>(
      clEnqueueMapBuffer(q, b_->results_host, CL_TRUE, CL_MAP_READ | CL_MAP_WRITE, 0, result_bytes, 0,
                         nullptr, nullptr, &st));
  if (st != CL_SUCCESS) throw OclError("cannot map the peak list buffer", st);

  // Kernels and their fixed arguments.
  auto arg = [&](cl_kernel k, cl_uint i, size_t size, const void* v) {
    st = clSetKernelArg(k, i, size, v);
    if (st != CL_SUCCESS) throw OclError("cannot set argument " + std::to_string(i), st);
  };
  auto argMem = [&](cl_kernel k, cl_uint i, cl_mem m) { arg(k, i, sizeof(cl_mem), &m); };
  auto argInt = [&](cl_kernel k, cl_uint i, int v) { arg(k, i, sizeof(cl_int), &v); };
  auto argFloat = [&](cl_kernel k, cl_uint i, float v) { arg(k, i, sizeof(cl_float), &v); };
  auto kernelMax = [&](cl_kernel k) {
    size_t n = 0;
    clGetKernelWorkGroupInfo(k, dev.device, CL_KERNEL_WORK_GROUP_SIZE, sizeof n, &n, nullptr);
    return std::max<size_t>(1, std::min(n ? n : dev.max_work_group_size, dev.max_work_group_size));
  };
  const cl_mem input = zero_copy_ ? b_->input_host : b_->input_dev;

  const cl_int4 ka = {{c.chroma_a[0], c.chroma_a[1], c.chroma_a[2], 0}};
  const cl_int4 kb = {{c.chroma_b[0], c.chroma_b[1], c.chroma_b[2], 0}};
  const cl_int4 sites = {{c.red_x, c.red_y, c.blue_x, c.blue_y}};
  if (c.full_bayer) {
    b_->subsample = ctx_->createKernel("bayer_full_chroma");
    argMem(b_->subsample, 0, input);
    argInt(b_->subsample, 1, frame_stride_);
    argInt(b_->subsample, 2, ws);
    argInt(b_->subsample, 3, hs);
    arg(b_->subsample, 4, sizeof sites, &sites);
    arg(b_->subsample, 5, sizeof ka, &ka);
    arg(b_->subsample, 6, sizeof kb, &kb);
    arg(b_->subsample, 7, sizeof region, &region);
    argMem(b_->subsample, 8, b_->packed);
    argMem(b_->subsample, 9, b_->results);
  } else if (c.bayer) {
    b_->subsample = ctx_->createKernel("bayer_chroma");
    argMem(b_->subsample, 0, input);
    argInt(b_->subsample, 1, frame_stride_);
    argInt(b_->subsample, 2, ws);
    argInt(b_->subsample, 3, hs);
    argInt(b_->subsample, 4, c.red_x);
    argInt(b_->subsample, 5, c.red_y);
    argInt(b_->subsample, 6, c.blue_x);
    argInt(b_->subsample, 7, c.blue_y);
    arg(b_->subsample, 8, sizeof ka, &ka);
    arg(b_->subsample, 9, sizeof kb, &kb);
    arg(b_->subsample, 10, sizeof region, &region);
    argMem(b_->subsample, 11, b_->packed);
    argMem(b_->subsample, 12, b_->results);
  } else {
    b_->subsample = ctx_->createKernel("bgr_chroma");
    argMem(b_->subsample, 0, input);
    argInt(b_->subsample, 1, frame_stride_);
    argInt(b_->subsample, 2, ws);
    argInt(b_->subsample, 3, hs);
    arg(b_->subsample, 4, sizeof ka, &ka);
    arg(b_->subsample, 5, sizeof kb, &kb);
    arg(b_->subsample, 6, sizeof region, &region);
    argMem(b_->subsample, 7, b_->packed);
    argMem(b_->subsample, 8, b_->results);
  }
  {
    // The brightness reduction needs a power-of-two group of at most 256.
    const size_t m = floorPow2(std::min<size_t>(256, kernelMax(b_->subsample)));
    b_->subsample_local[0] = std::min<size_t>(16, m);
    b_->subsample_local[1] = m / b_->subsample_local[0];
  }

  b_->rectify = ctx_->createKernel("rectify_chroma");
  argMem(b_->rectify, 0, b_->packed);
  argInt(b_->rectify, 1, ws);
  argMem(b_->rectify, 2, b_->remap_index);
  argMem(b_->rectify, 3, b_->remap_frac);
  argInt(b_->rectify, 4, c.grid_width);
  argInt(b_->rectify, 5, c.grid_height);
  argFloat(b_->rectify, 6, luma_count_);
  argFloat(b_->rectify, 7, kPackedChromaScale);
  argMem(b_->rectify, 8, b_->results);
  argMem(b_->rectify, 9, b_->chroma);

  b_->gradient = ctx_->createKernel("gradient_dot");
  const int k = static_cast<int>(std::floor(c.gradient_scale));
  const float a = static_cast<float>(c.gradient_scale - k), na = 1 - a;
  argMem(b_->gradient, 0, b_->chroma);
  argInt(b_->gradient, 1, c.grid_width);
  argInt(b_->gradient, 2, c.grid_height);
  argInt(b_->gradient, 3, k);
  argFloat(b_->gradient, 4, a);
  argFloat(b_->gradient, 5, na);
  argMem(b_->gradient, 6, b_->gdot);
  const int use_forms = !c.gradient_forms.empty() && !c.circle_score ? 1 : 0;
  argMem(b_->gradient, 7, b_->forms);
  argMem(b_->gradient, 8, b_->form_plain_row);
  argInt(b_->gradient, 9, c.form_block);
  argInt(b_->gradient, 10, c.form_blocks_x);
  argInt(b_->gradient, 11, use_forms);

  b_->sat_rows = ctx_->createKernel("sat_rows");
  b_->sat_rows_local = floorPow2(std::min<size_t>(256, kernelMax(b_->sat_rows)));
  argMem(b_->sat_rows, 0, b_->gdot);
  argInt(b_->sat_rows, 1, c.grid_width);
  argInt(b_->sat_rows, 2, c.grid_height);
  argMem(b_->sat_rows, 3, b_->sat);
  arg(b_->sat_rows, 4, b_->sat_rows_local * 4, nullptr);

  b_->sat_cols = ctx_->createKernel("sat_columns");
  {
    const size_t m = floorPow2(std::min<size_t>(1024, kernelMax(b_->sat_cols)));
    b_->sat_cols_local[0] = std::min<size_t>(32, m);
    b_->sat_cols_local[1] = std::min<size_t>(32, m / b_->sat_cols_local[0]);
  }
  argMem(b_->sat_cols, 0, b_->sat);
  argInt(b_->sat_cols, 1, c.grid_width);
  argInt(b_->sat_cols, 2, c.grid_height);
  arg(b_->sat_cols, 3, b_->sat_cols_local[0] * b_->sat_cols_local[1] * 4, nullptr);

  if (c.circle_score) {
    b_->score_k = ctx_->createKernel("score_circle_min");
    argMem(b_->score_k, 0, b_->sat);
    argInt(b_->score_k, 1, c.grid_width);
    argInt(b_->score_k, 2, c.grid_height);
    argMem(b_->score_k, 3, b_->half);
    argInt(b_->score_k, 4, circle_rows);
    argFloat(b_->score_k, 5, circle_norm);
    argMem(b_->score_k, 6, b_->score);
  } else {
    b_->score_k = ctx_->createKernel("score_quadrant_min");
    const int r = c.quadrant_radius, q = c.inner_corner;
    argMem(b_->score_k, 0, b_->sat);
    argInt(b_->score_k, 1, c.grid_width);
    argInt(b_->score_k, 2, c.grid_height);
    argInt(b_->score_k, 3, r);
    argInt(b_->score_k, 4, q);
    argFloat(b_->score_k, 5, 1.0f / (4 * kGradientFixedPoint * (r * r - q * q)));
    argMem(b_->score_k, 6, b_->score);
  }

  b_->peaks = ctx_->createKernel("find_peaks");
  argMem(b_->peaks, 0, b_->score);
  argMem(b_->peaks, 1, b_->mask);
  argInt(b_->peaks, 2, c.grid_width);
  argInt(b_->peaks, 3, c.grid_height);
  argInt(b_->peaks, 4, c.margin);
  argFloat(b_->peaks, 5, lowThreshold() * c.energy_floor);  // ratio > t needs raw > t * floor
  argFloat(b_->peaks, 6, lowThreshold());
  argMem(b_->peaks, 7, b_->chroma);
  argInt(b_->peaks, 8, k);
  argFloat(b_->peaks, 9, a);
  argFloat(b_->peaks, 10, na);
  argInt(b_->peaks, 11, c.energy_window);
  argFloat(b_->peaks, 12, c.energy_floor);
  argMem(b_->peaks, 13, input);
  argInt(b_->peaks, 14, frame_stride_);
  argInt(b_->peaks, 15, c.full_bayer ? 2 : (c.bayer ? 1 : 0));
  arg(b_->peaks, 16, sizeof sites, &sites);
  argInt(b_->peaks, 17, ws);
  argInt(b_->peaks, 18, hs);
  argMem(b_->peaks, 19, b_->remap_index);
  argMem(b_->peaks, 20, b_->remap_frac);
  if (fp64_) {
    const double r = c.color_radius;
    arg(b_->peaks, 21, sizeof r, &r);
  } else {
    argFloat(b_->peaks, 21, static_cast<float>(c.color_radius));
  }
  argMem(b_->peaks, 22, b_->results);
  argInt(b_->peaks, 23, capacity_);
  argMem(b_->peaks, 24, b_->forms);
  argMem(b_->peaks, 25, b_->form_plain);
  argInt(b_->peaks, 26, c.form_block);
  argInt(b_->peaks, 27, c.form_blocks_x);
  argInt(b_->peaks, 28, use_forms);

  b_->streak_coarse_k = ctx_->createKernel("streak_coarse");
  argMem(b_->streak_coarse_k, 0, b_->chroma);
  argInt(b_->streak_coarse_k, 1, c.grid_width);
  argInt(b_->streak_coarse_k, 2, c.streak_factor);
  argInt(b_->streak_coarse_k, 3, c.streak_coarse_width);
  argInt(b_->streak_coarse_k, 4, c.streak_coarse_height);
  argMem(b_->streak_coarse_k, 5, b_->streak_coarse);
  argMem(b_->streak_coarse_k, 6, b_->streak_list);

  b_->streak_score_k = ctx_->createKernel("streak_score");
  argMem(b_->streak_score_k, 0, b_->streak_coarse);
  argInt(b_->streak_score_k, 1, c.streak_coarse_width);
  argInt(b_->streak_score_k, 2, c.streak_coarse_height);
  argInt(b_->streak_score_k, 3, c.streak_lattice_width);
  argInt(b_->streak_score_k, 4, c.streak_lattice_height);
  argInt(b_->streak_score_k, 5, c.streak_margin);
  argMem(b_->streak_score_k, 6, b_->streak_shape);
  argFloat(b_->streak_score_k, 7, c.streak_floor);
  argInt(b_->streak_score_k, 8, c.streak_gate_reach);
  argFloat(b_->streak_score_k, 9, c.streak_gate);
  argMem(b_->streak_score_k, 10, b_->streak_score);
  argMem(b_->streak_score_k, 11, b_->streak_orient);

  b_->streak_peaks_k = ctx_->createKernel("streak_peaks");
  {
    cl_kernel sk = b_->streak_peaks_k;
    argMem(sk, 0, b_->streak_score);
    argMem(sk, 1, b_->streak_orient);
    argMem(sk, 2, b_->streak_mask);
    argInt(sk, 3, c.streak_coarse_width);
    argInt(sk, 4, c.streak_lattice_width);
    argInt(sk, 5, c.streak_lattice_height);
    argFloat(sk, 6, c.streak_threshold);
    argMem(sk, 7, b_->streak_shape);
    argMem(sk, 8, b_->streak_coarse);
    argInt(sk, 9, c.streak_factor);
    argMem(sk, 10, b_->chroma);
    argInt(sk, 11, c.grid_width);
    argInt(sk, 12, c.grid_height);
    argFloat(sk, 13, c.streak_refine_along);
    argFloat(sk, 14, c.streak_refine_across);
    argMem(sk, 15, input);
    argInt(sk, 16, frame_stride_);
    argInt(sk, 17, c.full_bayer ? 2 : (c.bayer ? 1 : 0));
    arg(sk, 18, sizeof sites, &sites);
    argInt(sk, 19, ws);
    argInt(sk, 20, hs);
    argMem(sk, 21, b_->remap_index);
    argMem(sk, 22, b_->remap_frac);
    if (fp64_) {
      const double r = c.color_radius;
      arg(sk, 23, sizeof r, &r);
    } else {
      argFloat(sk, 23, static_cast<float>(c.color_radius));
    }
    argMem(sk, 24, b_->streak_list);
    argInt(sk, 25, c.streak_capacity);
  }

  size_t pixel_max = std::min(kernelMax(b_->rectify), kernelMax(b_->gradient));
  pixel_max = std::min({pixel_max, kernelMax(b_->score_k), kernelMax(b_->peaks), kernelMax(b_->streak_coarse_k),
                        kernelMax(b_->streak_score_k), kernelMax(b_->streak_peaks_k), size_t{256}});
  pixel_max = floorPow2(pixel_max);
  b_->pixel_local[0] = std::min<size_t>(32, pixel_max);
  b_->pixel_local[1] = pixel_max / b_->pixel_local[0];
}

OclEngine::~OclEngine() {
  if (!b_ || !ctx_) return;
  cl_command_queue q = ctx_->queue();
  if (mapped_) clEnqueueUnmapMemObject(q, b_->input_host, mapped_, 0, nullptr, nullptr);
  if (b_->results_mapped)
    clEnqueueUnmapMemObject(q, b_->results_host, b_->results_mapped, 0, nullptr, nullptr);
  clFinish(q);
}

uint8_t* OclEngine::frameBuffer() {
  if (mapped_) return mapped_;
  cl_int st = CL_SUCCESS;
  mapped_ = static_cast<uint8_t*>(clEnqueueMapBuffer(ctx_->queue(), b_->input_host, CL_TRUE,
                                                     CL_MAP_WRITE_INVALIDATE_REGION, 0, frame_bytes_,
                                                     0, nullptr, nullptr, &st));
  if (st != CL_SUCCESS) {
    mapped_ = nullptr;
    fail("mapping the frame buffer", st);
  }
  return mapped_;
}

bool OclEngine::fail(const char* what, int status) {
  error_ = std::string("OpenCL ") + what + " failed (" + oclStatusName(status) + ") on " +
           ctx_->device().device_name;
  b_->releaseEvents();
  // Leave the counters as a fresh frame expects them.
  clFinish(ctx_->queue());
  const uint32_t zeros[kHeaderWords] = {0, 0, 0, 0};
  clEnqueueWriteBuffer(ctx_->queue(), b_->results, CL_TRUE, 0, sizeof zeros, zeros, 0, nullptr, nullptr);
  return false;
}

bool OclEngine::run() { return runPeaks() && runStreaks(StreakLevels{cfg_.streak_floor, cfg_.streak_gate}); }

bool OclEngine::runPeaks() {
  t_start_ = std::chrono::steady_clock::now();
  error_.clear();
  peaks_.clear();
  streak_peaks_.clear();
  peaks_found_ = 0;
  b_->releaseEvents();
  if (!mapped_ && !frameBuffer()) return false;
  cl_command_queue q = ctx_->queue();
  auto* ev = b_->events;
  cl_int st = CL_SUCCESS;
  if (zero_copy_) {
    st = clEnqueueUnmapMemObject(q, b_->input_host, mapped_, 0, nullptr, &ev[Buffers::kUpload]);
    mapped_ = nullptr;
  } else {
    st = clEnqueueWriteBuffer(q, b_->input_dev, CL_FALSE, 0, frame_bytes_, mapped_, 0, nullptr,
                              &ev[Buffers::kUpload]);
  }
  if (st != CL_SUCCESS) return fail("frame upload", st);

  const auto& c = cfg_;
  const size_t* pl = b_->pixel_local;
  const size_t grid_global[2] = {roundUp(c.grid_width, pl[0]), roundUp(c.grid_height, pl[1])};
  const size_t* sl = b_->subsample_local;
  const size_t src_global[2] = {roundUp(src_width_, sl[0]), roundUp(src_height_, sl[1])};
  const size_t rows_global = static_cast<size_t>(c.grid_height) * b_->sat_rows_local;
  const size_t* cl = b_->sat_cols_local;
  const size_t cols_global[2] = {roundUp(c.grid_width + 1, cl[0]), cl[1]};

  if ((st = clEnqueueNDRangeKernel(q, b_->subsample, 2, nullptr, src_global, sl, 0, nullptr,
                                   &ev[Buffers::kSubsample])) != CL_SUCCESS)
    return fail("Bayer subsampling", st);
  if ((st = clEnqueueNDRangeKernel(q, b_->rectify, 2, nullptr, grid_global, pl, 0, nullptr,
                                   &ev[Buffers::kRectify])) != CL_SUCCESS)
    return fail("rectification", st);
  if ((st = clEnqueueNDRangeKernel(q, b_->gradient, 2, nullptr, grid_global, pl, 0, nullptr,
                                   &ev[Buffers::kGradient])) != CL_SUCCESS)
    return fail("gradient", st);
  if ((st = clEnqueueNDRangeKernel(q, b_->sat_rows, 1, nullptr, &rows_global, &b_->sat_rows_local, 0,
                                   nullptr, &ev[Buffers::kSatRows])) != CL_SUCCESS)
    return fail("summed-area rows", st);
  if (!c.circle_score &&
      (st = clEnqueueNDRangeKernel(q, b_->sat_cols, 2, nullptr, cols_global, cl, 0, nullptr,
                                   &ev[Buffers::kSatCols])) != CL_SUCCESS)
    return fail("summed-area columns", st);
  if ((st = clEnqueueNDRangeKernel(q, b_->score_k, 2, nullptr, grid_global, pl, 0, nullptr,
                                   &ev[Buffers::kScore])) != CL_SUCCESS)
    return fail("blob score", st);
  if ((st = clEnqueueNDRangeKernel(q, b_->peaks, 2, nullptr, grid_global, pl, 0, nullptr,
                                   &ev[Buffers::kPeaks])) != CL_SUCCESS)
    return fail("peak extraction", st);
  const size_t coarse_global[2] = {roundUp(c.streak_coarse_width, pl[0]), roundUp(c.streak_coarse_height, pl[1])};
  if ((st = clEnqueueNDRangeKernel(q, b_->streak_coarse_k, 2, nullptr, coarse_global, pl, 0, nullptr,
                                   &ev[Buffers::kStreakCoarse])) != CL_SUCCESS)
    return fail("streak chroma", st);
  // Counters and the first peaks in one transfer; the rest only if needed.
  const int first = std::min(capacity_, kFirstPeaksRead);
  uint32_t* res = b_->results_mapped;
  if ((st = clEnqueueReadBuffer(q, b_->results, CL_TRUE, 0, (kHeaderWords + first * kPeakWords) * 4, res,
                                0, nullptr, &ev[Buffers::kDownload])) != CL_SUCCESS)
    return fail("peak list download", st);
  peaks_found_ = static_cast<int>(res[0]);
  const int n = std::min(peaks_found_, capacity_);
  if (n > first &&
      (st = clEnqueueReadBuffer(q, b_->results, CL_TRUE, (kHeaderWords + first * kPeakWords) * 4,
                                static_cast<size_t>(n - first) * kPeakWords * 4,
                                res + kHeaderWords + first * kPeakWords, 0, nullptr,
                                &ev[Buffers::kDownload2])) != CL_SUCCESS)
    return fail("peak list download", st);
  std::memcpy(&last_luma_mean_, &res[2], sizeof(float));
  const auto* found = reinterpret_cast<const OclPeak*>(res + kHeaderWords);
  peaks_.assign(found, found + n);
  // Strongest first; ties by position so the order does not depend on the
  // device's scheduling.
  std::sort(peaks_.begin(), peaks_.end(), [](const OclPeak& a, const OclPeak& b) {
    if (a.score != b.score) return a.score > b.score;
    if (a.y != b.y) return a.y < b.y;
    return a.x < b.x;
  });
  // The max_blobs strongest above the threshold, then every weak one (the
  // host keeps those near blobs).
  const auto weak = std::partition_point(peaks_.begin(), peaks_.end(),
                                         [&](const OclPeak& p) { return p.score > c.threshold; });
  const long keep = std::min<long>(weak - peaks_.begin(), std::max(0, c.max_blobs));
  peaks_.erase(peaks_.begin() + keep, weak);

  return true;
}

bool OclEngine::runStreaks(const StreakLevels& levels) {
  const auto& c = cfg_;
  cl_command_queue q = ctx_->queue();
  auto* ev = b_->events;
  cl_int st = CL_SUCCESS;
  const size_t* pl = b_->pixel_local;
  levels_ = levels;
  if ((st = clSetKernelArg(b_->streak_score_k, 7, sizeof(cl_float), &levels.floor)) != CL_SUCCESS ||
      (st = clSetKernelArg(b_->streak_score_k, 9, sizeof(cl_float), &levels.gate)) != CL_SUCCESS)
    return fail("streak levels", st);
  const size_t lattice_global[2] = {roundUp(c.streak_lattice_width, pl[0]),
                                    roundUp(c.streak_lattice_height, pl[1])};
  if ((st = clEnqueueNDRangeKernel(q, b_->streak_score_k, 2, nullptr, lattice_global, pl, 0, nullptr,
                                   &ev[Buffers::kStreakScore])) != CL_SUCCESS)
    return fail("streak score", st);
  if ((st = clEnqueueNDRangeKernel(q, b_->streak_peaks_k, 2, nullptr, lattice_global, pl, 0, nullptr,
                                   &ev[Buffers::kStreakPeaks])) != CL_SUCCESS)
    return fail("streak peaks", st);

  // The streak list is short: read whole.
  if ((st = clEnqueueReadBuffer(q, b_->streak_list, CL_TRUE, 0, streak_host_.size() * 4, streak_host_.data(),
                                0, nullptr, &ev[Buffers::kStreakDownload])) != CL_SUCCESS)
    return fail("streak list download", st);
  {
    const int ns = std::min(static_cast<int>(streak_host_[0]), c.streak_capacity);
    const auto* sp = reinterpret_cast<const OclPeak*>(streak_host_.data() + kHeaderWords);
    streak_peaks_.assign(sp, sp + ns);
    std::sort(streak_peaks_.begin(), streak_peaks_.end(), [](const OclPeak& a, const OclPeak& b) {
      if (a.score != b.score) return a.score > b.score;
      if (a.cell_y != b.cell_y) return a.cell_y < b.cell_y;
      return a.cell_x < b.cell_x;
    });
  }

  auto& t = times_;
  t.upload_ms = eventMs(ev[Buffers::kUpload], ev[Buffers::kUpload]);
  t.bayer_ms = eventMs(ev[Buffers::kSubsample], ev[Buffers::kSubsample]);
  t.rectify_ms = eventMs(ev[Buffers::kRectify], ev[Buffers::kRectify]);
  t.gradient_ms = eventMs(ev[Buffers::kGradient], ev[Buffers::kGradient]);
  t.sat_ms = eventMs(ev[Buffers::kSatRows], ev[Buffers::kSatRows]) +
             eventMs(ev[Buffers::kSatCols], ev[Buffers::kSatCols]);
  t.score_ms = eventMs(ev[Buffers::kScore], ev[Buffers::kScore]);
  t.peaks_ms = eventMs(ev[Buffers::kPeaks], ev[Buffers::kPeaks]);
  t.streak_ms = eventMs(ev[Buffers::kStreakCoarse], ev[Buffers::kStreakCoarse]) +
                eventMs(ev[Buffers::kStreakScore], ev[Buffers::kStreakPeaks]);  // the host works between
  t.download_ms = eventMs(ev[Buffers::kDownload], ev[Buffers::kDownload]) +
                  eventMs(ev[Buffers::kDownload2], ev[Buffers::kDownload2]) +
                  eventMs(ev[Buffers::kStreakDownload], ev[Buffers::kStreakDownload]);
  t.device_ms = eventMs(ev[Buffers::kUpload], ev[Buffers::kStreakDownload]);
  b_->releaseEvents();
  t.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_start_).count();
  return true;
}

double OclEngine::timeUploadOnly() {
  cl_command_queue q = ctx_->queue();
  cl_event e = nullptr;
  cl_int st;
  if (zero_copy_) {
    if (!frameBuffer()) return 0;
    st = clEnqueueUnmapMemObject(q, b_->input_host, mapped_, 0, nullptr, &e);
    mapped_ = nullptr;
  } else {
    st = clEnqueueWriteBuffer(q, b_->input_dev, CL_TRUE, 0, frame_bytes_, mapped_, 0, nullptr, &e);
  }
  if (st != CL_SUCCESS) return 0;
  clWaitForEvents(1, &e);
  const double ms = eventMs(e, e);
  clReleaseEvent(e);
  return ms;
}

namespace {

template <class T>
std::vector<T> readAll(cl_command_queue q, cl_mem m, size_t count) {
  std::vector<T> out(count);
  clEnqueueReadBuffer(q, m, CL_TRUE, 0, count * sizeof(T), out.data(), 0, nullptr, nullptr);
  return out;
}

}  // namespace

std::vector<uint32_t> OclEngine::readPackedChroma() const {
  return readAll<uint32_t>(ctx_->queue(), b_->packed, 1ull * src_width_ * src_height_);
}
std::vector<float> OclEngine::readChroma() const {
  return readAll<float>(ctx_->queue(), b_->chroma, 2ull * cfg_.grid_width * cfg_.grid_height);
}
std::vector<int32_t> OclEngine::readGradient() const {
  return readAll<int32_t>(ctx_->queue(), b_->gdot, 1ull * cfg_.grid_width * cfg_.grid_height);
}
std::vector<uint32_t> OclEngine::readSat() const {
  return readAll<uint32_t>(ctx_->queue(), b_->sat, (cfg_.grid_width + 1ull) * (cfg_.grid_height + 1ull));
}
std::vector<float> OclEngine::readScore() const {
  return readAll<float>(ctx_->queue(), b_->score, 1ull * cfg_.grid_width * cfg_.grid_height);
}
std::vector<float> OclEngine::readStreakScore() const {
  return readAll<float>(ctx_->queue(), b_->streak_score,
                        1ull * cfg_.streak_lattice_width * cfg_.streak_lattice_height);
}
float OclEngine::lastLumaMean() const { return last_luma_mean_; }

}  // namespace dv

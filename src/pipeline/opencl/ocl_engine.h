#pragma once
// The OpenCL pixel pipeline for one camera, below the camera model: it takes
// the per-camera tables (remap, peak mask, radii) ready-made and turns raw
// frames into a sorted peak list. Depends only on OpenCL and the standard
// library, so the stand-alone GPU benchmark can link it without OpenCV.
//
// Memory (thesis A.2): the frame goes into driver-allocated host memory
// (CL_MEM_ALLOC_HOST_PTR). On devices that share memory with the host the
// kernels read it in place (map/unmap only); on discrete GPUs it stays mapped
// as pinned staging memory and is copied by DMA. Every buffer is created once
// in the constructor; run() allocates nothing of its own.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pipeline/opencl/ocl_runtime.h"
#include "pipeline/streak_windows.h"

namespace dv {

struct OclEngineConfig {
  // Input frame: 8-bit Bayer mosaic (bayer = true, even size) or 8-bit BGR.
  int image_width = 0, image_height = 0;
  bool bayer = true;
  // Full Bayer sampling (pipeline/bayer_full.h): a sample per pixel instead
  // of per 2x2 cell.
  bool full_bayer = false;
  int red_x = 0, red_y = 0, blue_x = 1, blue_y = 1;  // Bayer sites in the 2x2 cell

  // Rectified grid and its remap table into the RGBX image (image size / 2 for
  // subsampled Bayer): top-left sample index and fractions fx | fy << 8 in
  // 1/256 sample.
  int grid_width = 0, grid_height = 0;
  std::vector<int32_t> remap_index;
  std::vector<uint16_t> remap_frac;
  std::vector<uint8_t> peak_mask;  // 1 where a peak may be reported

  // The samples the table reads: columns [x_begin, x_end), rows [y_begin,
  // y_end) of the sample image; the frame brightness is measured there (on the
  // 2x2 cells under them for full Bayer sampling, as fullBayerCells).
  int region_x_begin = 0, region_x_end = 0, region_y_begin = 0, region_y_end = 0;

  // Chroma coefficients in 1/1024 (pipeline/bayer_subsample.h, ChromaFixed).
  int chroma_a[3] = {0, 0, 0}, chroma_b[3] = {0, 0, 0};
  double gradient_scale = 1;  // cells
  bool circle_score = false;
  int quadrant_radius = 2;    // cells (quadrant score)
  int inner_corner = 0;       // cells, inner corner left out of each quadrant
  double circle_radius = 2;   // cells (circle score)
  int energy_window = 2;      // cells, half-size of the gradient energy window
  float energy_floor = 0.01f; // added to the energy before the score ratio
  int margin = 4;             // cells next to the border that never hold a peak
  // Whitened gradient (pipeline/view_stretch.h, quadrant score only): 6
  // floats per block of form_block cells (product form, energy form), 1 per
  // block and per block row where it is plain. Empty: plain everywhere.
  int form_block = 16, form_blocks_x = 0;
  std::vector<float> gradient_forms;
  std::vector<uint8_t> form_plain, form_plain_row;
  double color_radius = 1;    // cells, disc of the mean blob color
  float threshold = 0.1f;  // on the ratio; raw scores must exceed threshold * energy_floor
  int max_blobs = 2000;
  // Weak peaks: ratio in (weak_threshold, threshold]; they are listed after
  // the blobs when max_weak_blobs > 0.
  float weak_threshold = 0;
  int max_weak_blobs = 0;

  // Fast-ball pass (pipeline/streak_score.h, StreakWindows): coarse grid,
  // per-orientation steps (along: step_x, step_y), inner half run, side and
  // end steps, refinement window (grid cells), threshold, floor and gate,
  // and the coarse peak mask.
  int streak_factor = 2, streak_coarse_width = 0, streak_coarse_height = 0, streak_margin = 7;
  int streak_lattice_width = 0, streak_lattice_height = 0;  // every other coarse cell
  int streak_step_x[4] = {1, 1, 0, -1}, streak_step_y[4] = {0, 1, 1, 1};
  int streak_inner[4] = {1, 1, 1, 1}, streak_side[4] = {3, 2, 3, 2}, streak_end[4] = {6, 4, 6, 4};
  float streak_refine_along = 10, streak_refine_across = 5;
  float streak_threshold = 0.45f, streak_floor = 1.0f;
  int streak_gate_reach = 6;  // coarse cells to the gate's samples
  float streak_gate = 0.2f;
  std::vector<uint8_t> streak_mask;
  int streak_capacity = 256;

  // Where to put the frame: true = CL_MEM_ALLOC_HOST_PTR (pinned / zero copy).
  bool pinned_input = true;
};

// Sets the fast-ball fields of `c` from the CPU reference's footprint `w`
// and its lattice mask, with the reference's thresholds.
void applyStreakWindows(const StreakWindows& w, std::vector<uint8_t> mask, OclEngineConfig& c);

// A peak on the grid, strongest first: interpolated position, score ratio,
// mean color, and the peak cell itself.
struct OclPeak {
  float x, y, score, r, g, b, cell_x, cell_y;
};

// Per-stage device times of the last frame from profiling events (ms), plus
// the host wall time of run() (upload to peak list on the host).
struct OclStageTimes {
  double upload_ms = 0, bayer_ms = 0, rectify_ms = 0, gradient_ms = 0, sat_ms = 0, score_ms = 0,
         peaks_ms = 0, streak_ms = 0, download_ms = 0;
  double device_ms = 0;  // first command's start to last command's end
  double wall_ms = 0;
};

class OclEngine {
 public:
  // Creates every buffer and kernel. Throws OclError (out of memory, ...)
  // or std::invalid_argument for an inconsistent config.
  OclEngine(std::shared_ptr<OclContext> ctx, OclEngineConfig config);
  ~OclEngine();
  OclEngine(const OclEngine&) = delete;
  OclEngine& operator=(const OclEngine&) = delete;

  const OclEngineConfig& config() const { return cfg_; }
  const OclContext& context() const { return *ctx_; }
  // Bytes of one input frame, and its row stride.
  size_t frameBytes() const { return frame_bytes_; }
  int frameStride() const { return frame_stride_; }
  // True when the device reads the frame in place (no copy to the device).
  bool zeroCopy() const { return zero_copy_; }

  // Host memory to write the next frame into (frameBytes(), rows of
  // frameStride()). Valid until run() is called. nullptr on failure (see error()).
  uint8_t* frameBuffer();
  // Processes the frame in frameBuffer(). False (and error() set) on an
  // OpenCL failure; never throws. run() is runPeaks() then runStreaks() at
  // the config's fixed levels; a caller that sets the fast-ball pass's
  // levels from the frame's peaks (streakLevels) calls the two itself.
  bool run();
  // Everything up to the peak list (and the streak pass's chroma).
  bool runPeaks();
  // The fast-ball pass's score and peaks at `levels`, after runPeaks().
  bool runStreaks(const StreakLevels& levels);
  const StreakLevels& lastStreakLevels() const { return levels_; }

  // Peaks above the threshold (up to max_blobs), then all weak peaks, each
  // part strongest first.
  const std::vector<OclPeak>& peaks() const { return peaks_; }
  // Streak peaks of the fast-ball pass, strongest first (ties by lattice
  // cell, row then column); x, y: the refined grid position, cell_x, cell_y:
  // the lattice peak cell.
  const std::vector<OclPeak>& streakPeaks() const { return streak_peaks_; }
  // Peaks found before truncation to max_blobs (may exceed the list).
  int peaksFound() const { return peaks_found_; }
  const OclStageTimes& times() const { return times_; }
  const std::string& error() const { return error_; }

  // Stage outputs of the last frame, read back for tests (not for hot paths).
  std::vector<uint32_t> readPackedChroma() const;  // int16 pairs per subsampled sample
  std::vector<float> readChroma() const;      // 2 floats per cell
  std::vector<int32_t> readGradient() const;  // fixed point, x 65536
  std::vector<uint32_t> readSat() const;      // (w+1) x (h+1)
  std::vector<float> readScore() const;
  std::vector<float> readStreakScore() const;  // score lattice
  float lastLumaMean() const;                 // frame brightness used by the last frame

  // Only the upload of one frame (for comparison with the end-to-end time).
  double timeUploadOnly();

 private:
  struct Buffers;
  bool fail(const char* what, int status);
  int weakCapacity() const { return cfg_.weak_threshold > 0 ? std::max(0, cfg_.max_weak_blobs) : 0; }
  // The ratio every reported peak exceeds: the weak threshold where weak
  // peaks are wanted.
  float lowThreshold() const {
    return weakCapacity() > 0 ? std::min(cfg_.threshold, cfg_.weak_threshold) : cfg_.threshold;
  }

  std::shared_ptr<OclContext> ctx_;
  OclEngineConfig cfg_;
  std::unique_ptr<Buffers> b_;
  size_t frame_bytes_ = 0;
  int frame_stride_ = 0;
  int src_width_ = 0, src_height_ = 0;
  bool zero_copy_ = false;
  uint8_t* mapped_ = nullptr;
  bool fp64_ = false;
  int capacity_ = 0;
  float luma_count_ = 1;
  std::vector<OclPeak> peaks_;
  std::vector<OclPeak> streak_peaks_;
  std::vector<uint32_t> streak_host_;  // the streak list read back
  int peaks_found_ = 0;
  OclStageTimes times_;
  std::string error_;
  float last_luma_mean_ = 0;
  StreakLevels levels_;
  std::chrono::steady_clock::time_point t_start_;  // of runPeaks, for the wall time
};

}  // namespace dv

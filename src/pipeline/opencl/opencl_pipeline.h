#pragma once
// The OpenCL backend of the pixel pipeline: the same stages and the same
// arithmetic as CpuPipeline (integer Bayer subsampling, float rectification
// and chroma in the reference's operation order, fixed-point gradient and
// modular summed-area table), run by OclEngine on one OpenCL device.
// Per-camera tables (remap, peak mask, radii) are built here with the CPU
// reference's own code, so both backends see identical tables.
#include <memory>
#include <string>

#include "pipeline/backend.h"
#include "pipeline/blob_color_gate.h"
#include "pipeline/blob_spacing.h"
#include "pipeline/opencl/ocl_engine.h"
#include "pipeline/streak_markings.h"
#include "pipeline/streak_score.h"

namespace dv {

class OpenClPipeline final : public PixelPipeline {
 public:
  // Throws InputError for camera problems (as CpuPipeline) and OclError for
  // device problems (build failure, out of memory, ...).
  OpenClPipeline(const CameraModel& camera, const FieldModel& field, const PipelineOptions& opt,
                 const OclDeviceInfo& device);
  ~OpenClPipeline() override;

  bool process(const cv::Mat& raw, BlobList& out) override;
  void expect(const ExpectedPlaces& places) override { expected_ = places; }
  const std::string& lastError() const override { return error_; }
  const RectifiedGrid& grid() const override { return grid_; }
  const StageTimes& times() const override { return times_; }
  double uploadMs() const override { return engine_->times().upload_ms; }
  const PipelineOptions& options() const override { return opt_; }
  const std::string& samplingNote() const override { return sampling_note_; }
  std::optional<ImagePx> gridToImage(GridPx g) const override;
  std::string name() const override;

  // The engine, for per-stage inspection in tests and benchmarks.
  OclEngine& engine() { return *engine_; }
  const OclEngine& engine() const { return *engine_; }
  double gradientScale() const { return engine_->config().gradient_scale; }
  int quadrantRadius() const { return engine_->config().quadrant_radius; }

 private:
  CameraModel camera_;
  PipelineOptions opt_;
  ExpectedPlaces expected_;  // weak peaks count near these too (blob.h)
  RectifiedGrid grid_;
  StreakWindows streak_;  // the fast-ball pass's footprint on this grid
  MarkingMask streak_markings_;  // grid cells on a field line (streak_markings.h)
  std::vector<MarkedStreak> streak_later_;  // streak candidates on a marking (reserved)
  std::unique_ptr<OclEngine> engine_;
  BlobSpacing spacing_;  // one blob per object
  BlobColorGate color_gate_;  // which peaks are colored enough (blob_color_gate.h)
  BlobSpacing reach_;    // where weak peaks may lie: near a blob
  StageTimes times_;
  std::string error_;
  std::string sampling_note_;
};

}  // namespace dv

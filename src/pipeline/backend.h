#pragma once
// Choosing the pixel pipeline backend: the CPU reference or OpenCL.
//
//   --backend auto    an OpenCL GPU if there is one (and it builds), else the
//                     CPU reference. OpenCL on a CPU (PoCL) is never chosen
//                     automatically: on this project's machines the CPU
//                     reference is faster than PoCL.
//   --backend cpu     the CPU reference.
//   --backend opencl  OpenCL on the selected device, any type; failure is an
//                     error that lists the platforms and devices found.
//   --opencl-platform / --opencl-device: index or name substring.
#include <memory>
#include <optional>
#include <opencv2/core.hpp>
#include <string>

#include "core/units.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "pipeline/blob.h"
#include "pipeline/pipeline_options.h"
#include "pipeline/rectified_grid.h"

namespace dv {

// What both backends offer (the same contract as CpuPipeline).
class PixelPipeline {
 public:
  virtual ~PixelPipeline() = default;
  // raw: CV_8UC1 Bayer or CV_8UC3 BGR of the calibration's image size. False
  // (out empty, lastError() set) on a bad frame or a device failure.
  virtual bool process(const cv::Mat& raw, BlobList& out) = 0;
  // Places where weak peaks also count from the next frame on, until set
  // again (blob.h).
  virtual void expect(const ExpectedPlaces& places) = 0;
  virtual const std::string& lastError() const = 0;
  virtual const RectifiedGrid& grid() const = 0;
  // Stage times of the last frame (OpenCL: from profiling events; total_ms is
  // the host wall time including the copy into pinned memory and transfers).
  virtual const StageTimes& times() const = 0;
  // Host -> device transfer of the last frame, ms (0 for the CPU backend).
  virtual double uploadMs() const { return 0; }
  // Options as used: bayer_sampling resolved for this camera (never Auto).
  virtual const PipelineOptions& options() const = 0;
  // How the mosaic is sampled and why, one line for the log (bayer_sampling.h).
  virtual const std::string& samplingNote() const = 0;
  virtual std::optional<ImagePx> gridToImage(GridPx g) const = 0;
  // "cpu" or "opencl <device name>".
  virtual std::string name() const = 0;
};

enum class Backend { Auto, Cpu, OpenCl };

struct BackendChoice {
  Backend backend = Backend::Auto;
  std::string opencl_platform;  // index or name substring; empty = any
  std::string opencl_device;    // index or name substring; empty = any
};

// "auto", "cpu", "opencl" (case-insensitive); false if unknown.
bool parseBackend(const char* text, Backend& out);
const char* backendName(Backend b);

// Builds the pipeline for one camera.
//  - Camera problems (no image size, sees no field): InputError, as CpuPipeline.
//  - OpenCL problems (no platform, no matching device, build failure, out of
//    memory) under Backend::OpenCl: InputError("--backend opencl", reason +
//    the devices found). Under Backend::Auto: the CPU reference, and `why`
//    (if given) says why OpenCL was not used.
// `why` also receives a one-line note of what was chosen.
std::unique_ptr<PixelPipeline> makePipeline(const CameraModel& camera, const FieldModel& field,
                                            const PipelineOptions& opt, const BackendChoice& choice,
                                            std::string* why = nullptr);

// The CPU reference behind the common interface.
std::unique_ptr<PixelPipeline> makeCpuPipeline(const CameraModel& camera, const FieldModel& field,
                                               const PipelineOptions& opt);

}  // namespace dv

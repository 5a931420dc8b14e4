#include "pipeline/backend.h"

#include <cctype>

#include "core/error.h"
#include "pipeline/cpu_pipeline.h"
#include "pipeline/opencl/opencl_pipeline.h"

namespace dv {

namespace {

class CpuPixelPipeline final : public PixelPipeline {
 public:
  CpuPixelPipeline(const CameraModel& camera, const FieldModel& field, const PipelineOptions& opt)
      : cpu_(camera, field, opt) {}
  bool process(const cv::Mat& raw, BlobList& out) override { return cpu_.process(raw, out); }
  void expect(const ExpectedPlaces& places) override { cpu_.expect(places); }
  const std::string& lastError() const override { return cpu_.lastError(); }
  const RectifiedGrid& grid() const override { return cpu_.grid(); }
  const StageTimes& times() const override { return cpu_.times(); }
  const PipelineOptions& options() const override { return cpu_.options(); }
  const std::string& samplingNote() const override { return cpu_.samplingNote(); }
  std::optional<ImagePx> gridToImage(GridPx g) const override { return cpu_.gridToImage(g); }
  std::string name() const override { return "cpu"; }

 private:
  CpuPipeline cpu_;
};

void note(std::string* why, const std::string& text) {
  if (why) *why = text;
}

}  // namespace

bool parseBackend(const char* text, Backend& out) {
  std::string s = text ? text : "";
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s == "auto") out = Backend::Auto;
  else if (s == "cpu") out = Backend::Cpu;
  else if (s == "opencl" || s == "ocl") out = Backend::OpenCl;
  else return false;
  return true;
}

const char* backendName(Backend b) {
  switch (b) {
    case Backend::Auto: return "auto";
    case Backend::Cpu: return "cpu";
    case Backend::OpenCl: return "opencl";
  }
  return "?";
}

std::unique_ptr<PixelPipeline> makeCpuPipeline(const CameraModel& camera, const FieldModel& field,
                                               const PipelineOptions& opt) {
  return std::make_unique<CpuPixelPipeline>(camera, field, opt);
}

std::unique_ptr<PixelPipeline> makePipeline(const CameraModel& camera, const FieldModel& field,
                                            const PipelineOptions& opt, const BackendChoice& choice,
                                            std::string* why) {
  if (choice.backend == Backend::Cpu) {
    note(why, "backend cpu");
    return makeCpuPipeline(camera, field, opt);
  }
  OclDeviceRequest req{choice.opencl_platform, choice.opencl_device, choice.backend == Backend::Auto};
  try {
    const OclDeviceInfo device = selectOpenClDevice(req);
    auto p = std::make_unique<OpenClPipeline>(camera, field, opt, device);
    note(why, "backend opencl on " + device.device_name + " (" + device.platform_name + ")");
    return p;
  } catch (const OclError& e) {
    if (choice.backend == Backend::OpenCl) throw InputError("--backend opencl", e.what());
    note(why, std::string("backend auto: using the CPU reference (") + e.what() + ")");
    return makeCpuPipeline(camera, field, opt);
  } catch (const std::invalid_argument& e) {
    // Tables the engine cannot use: a programming error, but never a crash.
    if (choice.backend == Backend::OpenCl) throw InputError("--backend opencl", e.what());
    note(why, std::string("backend auto: using the CPU reference (") + e.what() + ")");
    return makeCpuPipeline(camera, field, opt);
  }
}

}  // namespace dv

#pragma once
// OpenCL platform/device discovery, device selection and program building with
// an on-disk binary cache. Uses the OpenCL 1.2 C API only, so the same code
// runs on Intel, NVIDIA, AMD and PoCL; depends on nothing but the standard
// library (the stand-alone GPU benchmark links it without OpenCV).
#include <CL/cl.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace dv {

// Any OpenCL failure: what was attempted and the OpenCL status name.
class OclError : public std::runtime_error {
 public:
  OclError(const std::string& what, cl_int status = CL_SUCCESS);
  cl_int status() const { return status_; }

 private:
  cl_int status_;
};

// Name of an OpenCL status code ("CL_OUT_OF_RESOURCES", ...).
const char* oclStatusName(cl_int status);

struct OclDeviceInfo {
  int platform_index = 0;
  int device_index = 0;  // within its platform
  cl_platform_id platform = nullptr;
  cl_device_id device = nullptr;
  std::string platform_name, device_name, device_version, driver_version;
  bool is_gpu = false;
  bool image_support = false;
  bool host_unified_memory = false;  // shares memory with the host (iGPU, CPU)
  unsigned long long global_mem_bytes = 0;
  size_t max_work_group_size = 0;
};

// All devices of all platforms; empty (and *error set) when there is no
// platform or the ICD loader fails.
std::vector<OclDeviceInfo> listOpenClDevices(std::string* error = nullptr);

// Human-readable list, one line per device: "platform 0 (Portable Computing
// Language) device 0: pthread-... [CPU]". Used in every selection error.
std::string describeOpenClDevices(const std::vector<OclDeviceInfo>& devices);

// Which device to use. Empty strings mean "any"; a number selects by index,
// anything else by case-insensitive substring of the name.
struct OclDeviceRequest {
  std::string platform;
  std::string device;
  bool gpu_only = false;
};

// The first device that matches. Throws OclError listing what was found when
// nothing matches.
OclDeviceInfo selectOpenClDevice(const OclDeviceRequest& request);

// A context, one in-order profiling command queue and the built program of
// the embedded kernels, on one device. One per camera.
class OclContext {
 public:
  // Builds (or loads from the on-disk cache) the program from the embedded
  // kernel files. Throws OclError on any failure (build log included).
  explicit OclContext(const OclDeviceInfo& device, const std::string& build_options = "");
  ~OclContext();
  OclContext(const OclContext&) = delete;
  OclContext& operator=(const OclContext&) = delete;

  const OclDeviceInfo& device() const { return device_; }
  cl_context context() const { return context_; }
  cl_command_queue queue() const { return queue_; }
  cl_program program() const { return program_; }
  // True when the program came from the disk cache rather than a compile.
  bool programFromCache() const { return from_cache_; }
  // Whether kernels were built with double precision (cl_khr_fp64).
  bool fp64() const { return fp64_; }

  cl_kernel createKernel(const char* name) const;

 private:
  OclDeviceInfo device_;
  cl_context context_ = nullptr;
  cl_command_queue queue_ = nullptr;
  cl_program program_ = nullptr;
  bool from_cache_ = false;
  bool fp64_ = false;
};

// Directory of cached program binaries: $DV_OPENCL_CACHE, else
// $XDG_CACHE_HOME/dotvision/opencl, else ~/.cache/dotvision/opencl.
std::string openClCacheDir();

// All embedded kernel files as one program: common.cl first, then the
// others in name order.
std::string embeddedProgramSource();

}  // namespace dv

#include "pipeline/opencl/ocl_runtime.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "pipeline/opencl/embedded_kernels.h"

namespace dv {

namespace {

// PoCL's first platform query is not thread-safe (two cameras of serve
// starting at once crashed inside hwloc), nor is a shared program cache
// written by two builds at once: device listing and context set-up take turns.
std::mutex& openClSetupMutex() {
  static std::mutex m;
  return m;
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string platformString(cl_platform_id p, cl_platform_info what) {
  size_t n = 0;
  if (clGetPlatformInfo(p, what, 0, nullptr, &n) != CL_SUCCESS || n == 0) return {};
  std::string s(n, '\0');
  clGetPlatformInfo(p, what, n, s.data(), nullptr);
  while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
  return s;
}

std::string deviceString(cl_device_id d, cl_device_info what) {
  size_t n = 0;
  if (clGetDeviceInfo(d, what, 0, nullptr, &n) != CL_SUCCESS || n == 0) return {};
  std::string s(n, '\0');
  clGetDeviceInfo(d, what, n, s.data(), nullptr);
  while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
  return s;
}

template <class T>
T deviceValue(cl_device_id d, cl_device_info what) {
  T v{};
  clGetDeviceInfo(d, what, sizeof(T), &v, nullptr);
  return v;
}

// Matches a request string against an index or a name.
bool matches(const std::string& want, int index, const std::string& name) {
  if (want.empty()) return true;
  if (std::all_of(want.begin(), want.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
    return std::atoi(want.c_str()) == index;
  return lower(name).find(lower(want)) != std::string::npos;
}

// 64-bit FNV-1a: stable across runs and builds, good enough for a cache key.
uint64_t fnv1a(const std::string& s, uint64_t h = 1469598103934665603ull) {
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

OclError::OclError(const std::string& what, cl_int status)
    : std::runtime_error(status == CL_SUCCESS ? what : what + " (" + oclStatusName(status) + ")"),
      status_(status) {}

const char* oclStatusName(cl_int s) {
  switch (s) {
#define DV_CL_CASE(x) \
  case x: return #x;
    DV_CL_CASE(CL_SUCCESS)
    DV_CL_CASE(CL_DEVICE_NOT_FOUND)
    DV_CL_CASE(CL_DEVICE_NOT_AVAILABLE)
    DV_CL_CASE(CL_COMPILER_NOT_AVAILABLE)
    DV_CL_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    DV_CL_CASE(CL_OUT_OF_RESOURCES)
    DV_CL_CASE(CL_OUT_OF_HOST_MEMORY)
    DV_CL_CASE(CL_PROFILING_INFO_NOT_AVAILABLE)
    DV_CL_CASE(CL_MEM_COPY_OVERLAP)
    DV_CL_CASE(CL_IMAGE_FORMAT_MISMATCH)
    DV_CL_CASE(CL_IMAGE_FORMAT_NOT_SUPPORTED)
    DV_CL_CASE(CL_BUILD_PROGRAM_FAILURE)
    DV_CL_CASE(CL_MAP_FAILURE)
    DV_CL_CASE(CL_INVALID_VALUE)
    DV_CL_CASE(CL_INVALID_DEVICE)
    DV_CL_CASE(CL_INVALID_CONTEXT)
    DV_CL_CASE(CL_INVALID_COMMAND_QUEUE)
    DV_CL_CASE(CL_INVALID_MEM_OBJECT)
    DV_CL_CASE(CL_INVALID_BINARY)
    DV_CL_CASE(CL_INVALID_BUILD_OPTIONS)
    DV_CL_CASE(CL_INVALID_PROGRAM)
    DV_CL_CASE(CL_INVALID_PROGRAM_EXECUTABLE)
    DV_CL_CASE(CL_INVALID_KERNEL_NAME)
    DV_CL_CASE(CL_INVALID_KERNEL)
    DV_CL_CASE(CL_INVALID_ARG_INDEX)
    DV_CL_CASE(CL_INVALID_ARG_VALUE)
    DV_CL_CASE(CL_INVALID_ARG_SIZE)
    DV_CL_CASE(CL_INVALID_KERNEL_ARGS)
    DV_CL_CASE(CL_INVALID_WORK_DIMENSION)
    DV_CL_CASE(CL_INVALID_WORK_GROUP_SIZE)
    DV_CL_CASE(CL_INVALID_WORK_ITEM_SIZE)
    DV_CL_CASE(CL_INVALID_GLOBAL_OFFSET)
    DV_CL_CASE(CL_INVALID_EVENT_WAIT_LIST)
    DV_CL_CASE(CL_INVALID_EVENT)
    DV_CL_CASE(CL_INVALID_OPERATION)
    DV_CL_CASE(CL_INVALID_BUFFER_SIZE)
    DV_CL_CASE(CL_INVALID_GLOBAL_WORK_SIZE)
    DV_CL_CASE(CL_INVALID_PLATFORM)
#undef DV_CL_CASE
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";
    default: return "CL_UNKNOWN_ERROR";
  }
}

std::vector<OclDeviceInfo> listOpenClDevices(std::string* error) {
  std::lock_guard<std::mutex> lock(openClSetupMutex());
  std::vector<OclDeviceInfo> out;
  cl_uint np = 0;
  cl_int st = clGetPlatformIDs(0, nullptr, &np);
  if (st != CL_SUCCESS || np == 0) {
    if (error)
      *error = st == CL_SUCCESS ? "no OpenCL platform installed"
                                : std::string("no OpenCL platform (") + oclStatusName(st) + ")";
    return out;
  }
  std::vector<cl_platform_id> platforms(np);
  clGetPlatformIDs(np, platforms.data(), nullptr);
  for (cl_uint p = 0; p < np; ++p) {
    cl_uint nd = 0;
    if (clGetDeviceIDs(platforms[p], CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS) continue;
    std::vector<cl_device_id> devices(nd);
    clGetDeviceIDs(platforms[p], CL_DEVICE_TYPE_ALL, nd, devices.data(), nullptr);
    for (cl_uint d = 0; d < nd; ++d) {
      OclDeviceInfo info;
      info.platform_index = static_cast<int>(p);
      info.device_index = static_cast<int>(d);
      info.platform = platforms[p];
      info.device = devices[d];
      info.platform_name = platformString(platforms[p], CL_PLATFORM_NAME);
      info.device_name = deviceString(devices[d], CL_DEVICE_NAME);
      info.device_version = deviceString(devices[d], CL_DEVICE_VERSION);
      info.driver_version = deviceString(devices[d], CL_DRIVER_VERSION);
      info.is_gpu = (deviceValue<cl_device_type>(devices[d], CL_DEVICE_TYPE) & CL_DEVICE_TYPE_GPU) != 0;
      info.image_support = deviceValue<cl_bool>(devices[d], CL_DEVICE_IMAGE_SUPPORT) != CL_FALSE;
      info.host_unified_memory =
          deviceValue<cl_bool>(devices[d], CL_DEVICE_HOST_UNIFIED_MEMORY) != CL_FALSE;
      info.global_mem_bytes = deviceValue<cl_ulong>(devices[d], CL_DEVICE_GLOBAL_MEM_SIZE);
      info.max_work_group_size = deviceValue<size_t>(devices[d], CL_DEVICE_MAX_WORK_GROUP_SIZE);
      out.push_back(std::move(info));
    }
  }
  if (out.empty() && error) *error = "OpenCL platforms found, but no devices";
  return out;
}

std::string describeOpenClDevices(const std::vector<OclDeviceInfo>& devices) {
  if (devices.empty()) return "no OpenCL devices found";
  std::ostringstream s;
  s << "OpenCL devices found:";
  for (const auto& d : devices)
    s << "\n  platform " << d.platform_index << " (" << d.platform_name << ") device "
      << d.device_index << ": " << d.device_name << " [" << (d.is_gpu ? "GPU" : "not GPU")
      << (d.image_support ? "" : ", no image support") << "]";
  return s.str();
}

OclDeviceInfo selectOpenClDevice(const OclDeviceRequest& req) {
  std::string why;
  const auto devices = listOpenClDevices(&why);
  if (devices.empty()) throw OclError(why);
  for (const auto& d : devices) {
    if (!matches(req.platform, d.platform_index, d.platform_name)) continue;
    if (!matches(req.device, d.device_index, d.device_name)) continue;
    if (req.gpu_only && !d.is_gpu) continue;
    return d;
  }
  std::string want;
  if (!req.platform.empty()) want += " platform '" + req.platform + "'";
  if (!req.device.empty()) want += " device '" + req.device + "'";
  if (req.gpu_only) want += " of type GPU";
  if (want.empty()) want = " any device";
  throw OclError("no OpenCL device matches" + want + "; " + describeOpenClDevices(devices));
}

std::string openClCacheDir() {
  if (const char* e = std::getenv("DV_OPENCL_CACHE"); e && *e) return e;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
    return std::string(x) + "/dotvision/opencl";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/dotvision/opencl";
  return (std::filesystem::temp_directory_path() / "dotvision-opencl").string();
}

std::string embeddedProgramSource() {
  std::vector<const EmbeddedKernel*> files;
  for (int i = 0; i < embeddedKernelCount(); ++i) files.push_back(&embeddedKernels()[i]);
  std::sort(files.begin(), files.end(),
            [](const auto* a, const auto* b) {
              // common.cl (shared definitions) first, the stages in name order.
              const bool ca = std::string_view(a->name) == "common.cl";
              const bool cb = std::string_view(b->name) == "common.cl";
              if (ca != cb) return ca;
              return std::string_view(a->name) < b->name;
            });
  std::string src;
  for (const auto* f : files) {
    src += "// ---- ";
    src += f->name;
    src += " ----\n";
    src += f->source;
    src += "\n";
  }
  return src;
}

OclContext::OclContext(const OclDeviceInfo& device, const std::string& build_options)
    : device_(device) {
  std::lock_guard<std::mutex> lock(openClSetupMutex());
  cl_int st = CL_SUCCESS;
  const cl_context_properties props[] = {CL_CONTEXT_PLATFORM,
                                         reinterpret_cast<cl_context_properties>(device.platform), 0};
  context_ = clCreateContext(props, 1, &device.device, nullptr, nullptr, &st);
  if (st != CL_SUCCESS) throw OclError("cannot create an OpenCL context on " + device.device_name, st);
  queue_ = clCreateCommandQueue(context_, device.device, CL_QUEUE_PROFILING_ENABLE, &st);
  if (st != CL_SUCCESS) {
    clReleaseContext(context_);
    throw OclError("cannot create a command queue on " + device.device_name, st);
  }

  // Double precision where the device has it (the CPU reference's disc test
  // is in double); correctly rounded division where offered, so divisions
  // agree with the CPU to the last bit.
  const std::string extensions = deviceString(device.device, CL_DEVICE_EXTENSIONS);
  fp64_ = extensions.find("cl_khr_fp64") != std::string::npos;
  const auto fp_config = deviceValue<cl_device_fp_config>(device.device, CL_DEVICE_SINGLE_FP_CONFIG);
  std::string options = "-cl-std=CL1.2";
  if (fp64_) options += " -DDV_FP64";
  if (fp_config & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) options += " -cl-fp32-correctly-rounded-divide-sqrt";
  if (!build_options.empty()) options += " " + build_options;
  const std::string source = embeddedProgramSource();
  const uint64_t key = fnv1a(options, fnv1a(source, fnv1a(device.platform_name + "|" + device.device_name +
                                                         "|" + device.device_version + "|" +
                                                         device.driver_version)));
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.bin", static_cast<unsigned long long>(key));
  const std::filesystem::path cache_file = std::filesystem::path(openClCacheDir()) / name;

  // Try the cached binary first; any problem with it just means a fresh build.
  {
    std::ifstream in(cache_file, std::ios::binary);
    std::vector<unsigned char> bin((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!bin.empty()) {
      const unsigned char* ptr = bin.data();
      size_t len = bin.size();
      cl_int bin_status = CL_SUCCESS;
      cl_program p = clCreateProgramWithBinary(context_, 1, &device.device, &len, &ptr, &bin_status, &st);
      if (st == CL_SUCCESS && bin_status == CL_SUCCESS &&
          clBuildProgram(p, 1, &device.device, options.c_str(), nullptr, nullptr) == CL_SUCCESS) {
        program_ = p;
        from_cache_ = true;
      } else if (p) {
        clReleaseProgram(p);
      }
    }
  }
  if (!program_) {
    const char* text = source.c_str();
    const size_t len = source.size();
    cl_program p = clCreateProgramWithSource(context_, 1, &text, &len, &st);
    if (st != CL_SUCCESS) {
      clReleaseCommandQueue(queue_);
      clReleaseContext(context_);
      throw OclError("cannot create the OpenCL program", st);
    }
    st = clBuildProgram(p, 1, &device.device, options.c_str(), nullptr, nullptr);
    if (st != CL_SUCCESS) {
      size_t n = 0;
      clGetProgramBuildInfo(p, device.device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
      std::string log(n, '\0');
      clGetProgramBuildInfo(p, device.device, CL_PROGRAM_BUILD_LOG, n, log.data(), nullptr);
      clReleaseProgram(p);
      clReleaseCommandQueue(queue_);
      clReleaseContext(context_);
      if (log.size() > 4000) log.resize(4000);
      throw OclError("OpenCL kernel build failed on " + device.device_name + ":\n" + log, st);
    }
    program_ = p;
    // Store the binary for the next run; a failure to write is not an error.
    size_t bin_size = 0;
    if (clGetProgramInfo(p, CL_PROGRAM_BINARY_SIZES, sizeof bin_size, &bin_size, nullptr) == CL_SUCCESS &&
        bin_size > 0) {
      std::vector<unsigned char> bin(bin_size);
      unsigned char* ptr = bin.data();
      if (clGetProgramInfo(p, CL_PROGRAM_BINARIES, sizeof ptr, &ptr, nullptr) == CL_SUCCESS) {
        std::error_code ec;
        std::filesystem::create_directories(cache_file.parent_path(), ec);
        const auto tmp = cache_file.string() + ".tmp" + std::to_string(reinterpret_cast<uintptr_t>(this));
        std::ofstream out(tmp, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
        out.close();
        if (out) std::filesystem::rename(tmp, cache_file, ec);  // atomic: readers never see half a file
        else std::filesystem::remove(tmp, ec);
      }
    }
  }
}

OclContext::~OclContext() {
  if (program_) clReleaseProgram(program_);
  if (queue_) clReleaseCommandQueue(queue_);
  if (context_) clReleaseContext(context_);
}

cl_kernel OclContext::createKernel(const char* name) const {
  cl_int st = CL_SUCCESS;
  cl_kernel k = clCreateKernel(program_, name, &st);
  if (st != CL_SUCCESS) throw OclError(std::string("cannot create OpenCL kernel ") + name, st);
  return k;
}

}  // namespace dv

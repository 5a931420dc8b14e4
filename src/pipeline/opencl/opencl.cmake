# OpenCL backend build steps, included from the top-level CMakeLists.txt after
# dv_pipeline exists.
#  - kernels/*.cl become a generated C++ source compiled into dv_pipeline.
#  - dotvision_ocl_bench: a stand-alone frame benchmark that needs only the C++
#    runtime (linked statically) and libOpenCL.so.1, for GPU machines without
#    the project's other libraries.
file(GLOB DV_KERNEL_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/kernels/*.cl)
set(DV_EMBEDDED_KERNELS_CPP ${PROJECT_BINARY_DIR}/kernels/embedded_kernels.cpp)
dv_embed_text_files(dv_pipeline Kernel pipeline/opencl/embedded_kernels.h ${DV_EMBEDDED_KERNELS_CPP}
                    ${DV_KERNEL_FILES})
target_compile_definitions(dv_pipeline PUBLIC CL_TARGET_OPENCL_VERSION=120)

# The engine itself uses nothing but OpenCL and the standard library.
set(DV_OCL_ENGINE_SRCS
  ${PROJECT_SOURCE_DIR}/src/pipeline/opencl/ocl_runtime.cpp
  ${PROJECT_SOURCE_DIR}/src/pipeline/opencl/ocl_engine.cpp
  ${DV_EMBEDDED_KERNELS_CPP})
add_executable(dotvision_ocl_bench
  ${PROJECT_SOURCE_DIR}/bench/standalone/ocl_frame_bench.cpp ${DV_OCL_ENGINE_SRCS})
target_include_directories(dotvision_ocl_bench PRIVATE ${PROJECT_SOURCE_DIR}/src)
target_compile_definitions(dotvision_ocl_bench PRIVATE CL_TARGET_OPENCL_VERSION=120)
target_link_libraries(dotvision_ocl_bench PRIVATE OpenCL::OpenCL Threads::Threads)
target_link_options(dotvision_ocl_bench PRIVATE -static-libstdc++ -static-libgcc)

// Still images as the frame sources read them (src/io/frame_source.cpp):
// the format, size, truncation and chunk checks, then OpenCV's decoders
// (PNG, JPEG, PNM, BMP, TIFF).
// The first byte picks the file name's extension.
#include <opencv2/core/utils/logger.hpp>

#include "fuzz_input.h"
#include "io/frame_source.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  // The frame source refuses headers above kMaxImagePixels (64 Mpx) itself.
  // OpenCV's own pixel limit cannot be lowered from here: it reads
  // OPENCV_IO_MAX_IMAGE_PIXELS once, as the library loads.
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* kNames[] = {"f.png", "f.jpg", "f.pgm", "f.ppm", "f.bmp", "f.tif"};
  const std::string path = dv::fuzz::inputFile(data + 1, size - 1, kNames[data[0] % 6]);
  dv::fuzz::expectOnlyInputErrors([&] {
    auto source = dv::openFrameSource(path, {});
    dv::Frame f;
    while (source->next(f)) {
    }
  });
  return 0;
}

// A GenICam camera buffer as the live source reads it (take() in
// src/camera/genicam_source.cpp, after Aravis has put the packets
// together): the pixel format, width and height its leader claims, the
// frame ids of two successive buffers, and the payload that came, reduced
// to the Frame's 8-bit image. Input: a 20-byte header (PFNC code u32,
// width i32, height i32, previous and current frame id u32), then the payload.
#include <opencv2/core.hpp>

#include <cstdlib>
#include <cstring>

#include "camera/frame_id_gap.h"
#include "camera/genicam_pixels.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  struct {
    uint32_t pfnc;
    int32_t width, height;
    uint32_t previous_id, id;
  } h;
  if (size < sizeof h) return 0;
  std::memcpy(&h, data, sizeof h);
  const uint32_t pfnc = h.pfnc;
  volatile uint64_t missed = dv::missedFrameIds(h.previous_id, h.id);
  (void)missed;
  const auto layout = dv::genicamPixelLayout(pfnc);
  if (!layout) {
    if (dv::unusablePixelFormatReason(pfnc, "PixelFormat").empty()) std::abort();
    return 0;
  }
  static cv::Mat out;  // reused across runs, as the source reuses its frame
  const uint8_t* payload = data + sizeof h;
  const size_t n = size - sizeof h;
  if (!dv::convertGenicamImage(payload, n, h.width, h.height, *layout, out)) return 0;
  // Taken: the image is what the leader claimed, and the payload covered it.
  const int channels = layout->format == dv::PixelFormat::Bgr8 ? 3 : 1;
  if (out.cols != h.width || out.rows != h.height || out.channels() != channels ||
      dv::genicamImageBytes(*layout, h.width, h.height) > n)
    std::abort();
  return 0;
}

#pragma once
// GenICam (PFNC) pixel formats as dotvision sees them: which ones carry a
// Bayer mosaic or color, how their bits are laid out, and the reduction of
// a camera buffer to the Frame's 8-bit image (Bayer mosaic or BGR).
// Independent of Aravis: formats are the PFNC 32-bit codes.
#include <opencv2/core/mat.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "io/frame_source.h"

namespace dv {

enum class PixelPacking {
  Bits8,         // one byte per sample (Bayer 8, RGB8, BGR8)
  Unpacked16,    // 10/12/16 bits in little-endian 16-bit words, value in the low bits
  GigePacked,    // GigE Vision "...Packed": 2 pixels in 3 bytes, high 8 bits in bytes 0 and 2
  Pfnc10p,       // PFNC "10p": 4 pixels in 5 bytes, LSB first
  Pfnc12p,       // PFNC "12p": 2 pixels in 3 bytes, LSB first
};

struct GenicamPixelLayout {
  PixelFormat format;   // what the Frame holds (Bayer layout or Bgr8)
  PixelPacking packing;
  int bits;             // significant bits per sample
  bool rgb_order;       // 3-channel formats: true for RGB8 (swapped to BGR)
};

// The layout of a PFNC code dotvision can use; nullopt for the others.
std::optional<GenicamPixelLayout> genicamPixelLayout(uint32_t pfnc);

// True for monochrome formats (Mono8, Mono12, ...): no color, refused.
bool isMonoPixelFormat(uint32_t pfnc);

// Preference when the camera's current format is unusable and dotvision
// picks one: higher is better (8-bit Bayer, then deeper Bayer, then RGB);
// 0 for unusable formats.
int genicamFormatPreference(uint32_t pfnc);

// Why `name` (PFNC code `pfnc`) cannot be used, for messages.
std::string unusablePixelFormatReason(uint32_t pfnc, const std::string& name);

// Bytes one width x height image takes in `layout`.
size_t genicamImageBytes(const GenicamPixelLayout& layout, int width, int height);

// Converts one camera image into `out` (created once per size, reused).
// Returns false when `size` is smaller than the image needs. No allocation
// once `out` has the right size.
bool convertGenicamImage(const uint8_t* data, size_t size, int width, int height,
                         const GenicamPixelLayout& layout, cv::Mat& out);

}  // namespace dv

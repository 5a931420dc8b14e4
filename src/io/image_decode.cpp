#include "io/image_decode.h"

#include <zlib.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <iostream>
#include <mutex>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "io/image_header.h"

namespace dv {
namespace {

// The first chunk whose CRC does not match, as a skip reason ("" if none).
// libpng would print its own "libpng error" line for such a file before
// failing, and for a damaged ancillary chunk decode it with a warning.
std::string pngChunkDamage(const unsigned char* bytes, size_t size) {
  size_t at = 8;
  while (at + 12 <= size) {
    const uint32_t length = uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 |
                            uint32_t(bytes[at + 2]) << 8 | uint32_t(bytes[at + 3]);
    if (length > size - at - 12) return "damaged PNG (chunk at byte " + std::to_string(at) + " runs past the end)";
    const unsigned char* type = bytes + at + 4;
    const unsigned char* crc = type + 4 + length;
    const uint32_t stored = uint32_t(crc[0]) << 24 | uint32_t(crc[1]) << 16 | uint32_t(crc[2]) << 8 | uint32_t(crc[3]);
    if (uint32_t(::crc32(0, type, 4 + length)) != stored) {
      return "damaged PNG (" + std::string(reinterpret_cast<const char*>(type), 4) + " chunk at byte " +
             std::to_string(at) + " fails its CRC)";
    }
    if (std::equal(type, type + 4, "IEND")) return "";
    at += 12 + length;
  }
  return "damaged PNG (no IEND chunk)";
}

// Decoders fill a truncated JPEG with gray and warn on stderr, and some PNG
// paths do similar; checking the end markers catches the cut before decoding.
// Returns an empty string when the bytes look complete.
std::string truncationReason(const unsigned char* bytes, size_t size) {
  static const unsigned char kPngMagic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static const unsigned char kPngEnd[8] = {'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  if (size >= 8 && std::equal(kPngMagic, kPngMagic + 8, bytes)) {
    if (!std::equal(kPngEnd, kPngEnd + 8, bytes + size - 8)) return "truncated PNG (no IEND chunk at the end)";
    return pngChunkDamage(bytes, size);
  }
  if (size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) {
    // Allow trailing padding after EOI, as some cameras write it.
    for (size_t i = size; i >= 2 && i + 64 >= size; --i)
      if (bytes[i - 2] == 0xff && bytes[i - 1] == 0xd9) return "";
    return "truncated JPEG (no end-of-image marker)";
  }
  return "";
}

// OpenCV's imdecode writes a damaged header's error to std::cerr itself
// ("imdecode_(''): can't read header: ...") before returning an empty image,
// which is then skipped with the project's reason. std::cerr is muted while
// any thread decodes (counted: two cameras decoding at once restore it
// once); the project writes to stderr through stdio and spdlog only.
class MutedStdCerr {
 public:
  MutedStdCerr() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (count_++ == 0) saved_ = std::cerr.rdbuf(nullptr);
  }
  ~MutedStdCerr() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (--count_ == 0) std::cerr.rdbuf(saved_);  // rdbuf() also clears the stream's state
  }
  MutedStdCerr(const MutedStdCerr&) = delete;
  MutedStdCerr& operator=(const MutedStdCerr&) = delete;

 private:
  static inline std::mutex mutex_;
  static inline int count_ = 0;
  static inline std::streambuf* saved_ = nullptr;
};

}  // namespace

std::string decodeImageBytes(const unsigned char* bytes, size_t size, cv::Mat& image) {
  if (size == 0) return "empty file";
  if (std::string why = truncationReason(bytes, size); !why.empty()) return why;
  const char* format = acceptedImageFormat(bytes, size);
  if (!format) return "not a PNG, JPEG, PNM, BMP or TIFF image (by its first bytes)";
  // The decoder would allocate whatever size it reads: one this check
  // cannot read never reaches it.
  const auto claimed = claimedImageSize(bytes, size);
  if (!claimed) return std::string("damaged ") + format + " header: no width and height could be read";
  if (tooManyPixels(*claimed)) {
    return "the header claims " + std::to_string(claimed->width) + "x" + std::to_string(claimed->height) +
           " pixels, above the limit of " + std::to_string(kMaxImagePixels >> 20) + " Mpx";
  }
  const cv::Mat encoded(1, static_cast<int>(size), CV_8UC1, const_cast<unsigned char*>(bytes));
  try {
    const MutedStdCerr quiet;
    image = cv::imdecode(encoded, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    image.release();
    return std::string("cannot decode the image: ") + e.what();
  }
  if (image.empty()) return "not a readable image (corrupt or unsupported format)";
  if (image.depth() != CV_8U) return "unsupported pixel depth (only 8-bit images are accepted)";
  return "";
}

cv::Mat readImageFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the file");
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path, "cannot read the file");
  cv::Mat image;
  if (std::string why = decodeImageBytes(bytes.data(), bytes.size(), image); !why.empty()) throw InputError(path, why);
  return image;
}

}  // namespace dv

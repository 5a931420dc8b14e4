#pragma once
// The width and height an image file's header claims, read before decoding:
// a header may promise far more pixels than the file holds, and the decoder
// would allocate them all before finding out.
#include <cstddef>
#include <cstdint>
#include <optional>

namespace dv {

struct ImageSize {
  int64_t width = 0;
  int64_t height = 0;
};

// Larger frames are refused unread: the largest machine-vision sensors in
// use are near 25 Mpx, so 64 Mpx leaves room and bounds a decoder's buffer.
inline constexpr int64_t kMaxImagePixels = int64_t(64) << 20;

// True when `s` holds more than kMaxImagePixels (without overflowing).
inline bool tooManyPixels(const ImageSize& s) {
  return s.width > 0 && s.height > kMaxImagePixels / s.width;
}

// The format the first bytes show, of those the frame sources take: "PNG",
// "JPEG", "PNM" (P1..P6), "BMP", "TIFF"; nullptr for any other, and for a
// file carrying the DICOM marker at byte 128 (OpenCV picks its decoder by
// content, and its DICOM reader aborts the process on a damaged file).
const char* acceptedImageFormat(const unsigned char* bytes, size_t size);

// The size in a PNG, JPEG, PGM/PPM/PBM, BMP or TIFF header, read as OpenCV's
// decoders read it; nullopt when the format is another or the header is too
// damaged to name one (the image is then refused: a size never checked must
// not reach a decoder).
std::optional<ImageSize> claimedImageSize(const unsigned char* bytes, size_t size);

}  // namespace dv

#pragma once
// One checked way from an image file's bytes to pixels, taken by the frame
// sources and the calibration images alike: nothing reaches OpenCV's
// decoders that could make them allocate an unchecked size, hand a file to
// a reader that aborts, or print their own lines.
#include <cstddef>
#include <opencv2/core.hpp>
#include <string>

namespace dv {

// Decodes a PNG, JPEG, PNM, BMP or TIFF file's bytes into `image` (8-bit,
// as many channels as stored). Returns "" or why the file is refused: empty,
// truncated, another format, a header whose size is unreadable or above
// kMaxImagePixels, the decoder's failure, another pixel depth.
std::string decodeImageBytes(const unsigned char* bytes, size_t size, cv::Mat& image);

// The image file at `path`, decoded as above; throws InputError(path, why)
// when it cannot be read or is refused.
cv::Mat readImageFile(const std::string& path);

}  // namespace dv

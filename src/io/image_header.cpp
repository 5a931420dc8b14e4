#include "io/image_header.h"

#include <algorithm>
#include <cctype>
#include <cstring>

namespace dv {
namespace {

uint32_t bigEndian(const unsigned char* p, int n) {
  uint32_t v = 0;
  for (int i = 0; i < n; ++i) v = v << 8 | p[i];
  return v;
}

int32_t littleEndian32(const unsigned char* p) {
  return int32_t(uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24);
}

// PNM: "P1".."P6", then width and height as decimal text separated by
// whitespace and '#' comments, read as OpenCV's decoder reads them: the
// character that ends a number is consumed whatever it is, so in "12#34"
// the '#' starts no comment and 34 is the next number.
std::optional<ImageSize> pnmSize(const unsigned char* b, size_t size) {
  size_t at = 2;
  int64_t values[2] = {0, 0};
  for (int64_t& value : values) {
    for (;;) {
      while (at < size && std::isspace(b[at])) ++at;
      if (at < size && b[at] == '#') {
        while (at < size && b[at] != '\n' && b[at] != '\r') ++at;
        continue;
      }
      break;
    }
    if (at >= size || !std::isdigit(b[at])) return std::nullopt;
    while (at < size && std::isdigit(b[at])) {
      value = value * 10 + (b[at++] - '0');
      if (value > (int64_t(1) << 40)) return ImageSize{value, 1};  // absurd already
    }
    ++at;  // the number's end, taken by the decoder
  }
  return ImageSize{values[0], values[1]};
}

// JPEG: the first start-of-frame marker (C0..CF but C4, C8, CC) holds
// height and width; other segments are skipped by their length. As libjpeg
// does, bytes before a marker are stepped over ("extraneous bytes"), and so
// are 0xFF fill bytes and stuffed FF 00 pairs.
std::optional<ImageSize> jpegSize(const unsigned char* b, size_t size) {
  size_t at = 2;
  while (at + 4 <= size) {
    const unsigned char marker = b[at + 1];
    if (b[at] != 0xff || marker == 0xff) {  // stray or fill byte
      ++at;
      continue;
    }
    if (marker == 0x00) {
      at += 2;
      continue;
    }
    if (marker == 0xd8 || marker == 0x01 || (marker >= 0xd0 && marker <= 0xd7)) {
      at += 2;  // markers without a length
      continue;
    }
    const uint32_t length = bigEndian(b + at + 2, 2);
    if (length < 2) return std::nullopt;
    if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc) {
      if (at + 9 > size) return std::nullopt;
      return ImageSize{bigEndian(b + at + 7, 2), bigEndian(b + at + 5, 2)};
    }
    at += 2 + length;
  }
  return std::nullopt;
}

// TIFF: the first image file directory's ImageWidth (256) and ImageLength
// (257) entries in the byte order the header names. libtiff takes any
// integer type there; those of up to four bytes are read (signed ones as
// their magnitude), and the largest of repeated entries; an entry of
// another type leaves the size unread.
std::optional<ImageSize> tiffSize(const unsigned char* b, size_t size) {
  const bool little = b[0] == 'I';
  auto read = [&](size_t at, int n) -> uint32_t {
    uint32_t v = 0;
    for (int i = 0; i < n; ++i) v |= uint32_t(b[at + i]) << (8 * (little ? i : n - 1 - i));
    return v;
  };
  const size_t ifd = read(4, 4);
  if (ifd + 2 > size) return std::nullopt;
  const size_t entries = read(ifd, 2);
  int64_t width = -1, height = -1;
  for (size_t i = 0; i < entries && ifd + 2 + 12 * (i + 1) <= size; ++i) {
    const size_t e = ifd + 2 + 12 * i;
    const uint32_t tag = read(e, 2), type = read(e + 2, 2);
    if (tag != 256 && tag != 257) continue;
    // BYTE, SHORT, LONG, then SBYTE, SSHORT, SLONG: 1, 3, 4, 6, 8, 9.
    const int bytes = type == 1 || type == 6 ? 1 : type == 3 || type == 8 ? 2 : type == 4 || type == 9 ? 4 : 0;
    if (bytes == 0) return std::nullopt;
    int64_t value = read(e + 8, bytes);
    if (type >= 6 && value >> (8 * bytes - 1)) value = (int64_t(1) << (8 * bytes)) - value;
    int64_t& side = tag == 256 ? width : height;
    side = std::max(side, value);
  }
  if (width < 0 || height < 0) return std::nullopt;
  return ImageSize{width, height};
}

}  // namespace

const char* acceptedImageFormat(const unsigned char* b, size_t size) {
  if (size >= 132 && std::memcmp(b + 128, "DICM", 4) == 0) return nullptr;
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size >= 8 && std::memcmp(b, kPng, 8) == 0) return "PNG";
  if (size >= 3 && b[0] == 0xff && b[1] == 0xd8 && b[2] == 0xff) return "JPEG";
  if (size >= 3 && b[0] == 'P' && b[1] >= '1' && b[1] <= '6' && std::isspace(b[2])) return "PNM";
  if (size >= 2 && b[0] == 'B' && b[1] == 'M') return "BMP";
  if (size >= 4 && (std::memcmp(b, "II*\0", 4) == 0 || std::memcmp(b, "MM\0*", 4) == 0)) return "TIFF";
  return nullptr;
}

std::optional<ImageSize> claimedImageSize(const unsigned char* b, size_t size) {
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size >= 24 && std::memcmp(b, kPng, 8) == 0 && std::memcmp(b + 12, "IHDR", 4) == 0) {
    return ImageSize{bigEndian(b + 16, 4), bigEndian(b + 20, 4)};
  }
  if (size >= 4 && b[0] == 0xff && b[1] == 0xd8) return jpegSize(b, size);
  if (size >= 3 && b[0] == 'P' && b[1] >= '1' && b[1] <= '6') return pnmSize(b, size);
  if (size >= 26 && b[0] == 'B' && b[1] == 'M') {
    // An OS/2 bitmap's 12-byte header holds 16-bit sizes; the others 32-bit
    // ones, a negative height for a top-down bitmap.
    if (littleEndian32(b + 14) == 12) return ImageSize{b[18] | b[19] << 8, b[20] | b[21] << 8};
    const int64_t w = littleEndian32(b + 18), h = littleEndian32(b + 22);
    return ImageSize{w < 0 ? -w : w, h < 0 ? -h : h};
  }
  if (size >= 8 && (std::memcmp(b, "II*\0", 4) == 0 || std::memcmp(b, "MM\0*", 4) == 0)) return tiffSize(b, size);
  return std::nullopt;
}

}  // namespace dv

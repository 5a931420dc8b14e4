#include "camera/genicam_pixels.h"

#include <opencv2/imgproc.hpp>

#include <cstring>
#include <limits>

namespace dv {

namespace {

// PFNC codes (GenICam Pixel Format Naming Convention), as GigE Vision and
// USB3 Vision cameras report them.
enum : uint32_t {
  kBayerGR8 = 0x01080008, kBayerRG8 = 0x01080009, kBayerGB8 = 0x0108000a, kBayerBG8 = 0x0108000b,
  kBayerGR10 = 0x0110000c, kBayerRG10 = 0x0110000d, kBayerGB10 = 0x0110000e, kBayerBG10 = 0x0110000f,
  kBayerGR12 = 0x01100010, kBayerRG12 = 0x01100011, kBayerGB12 = 0x01100012, kBayerBG12 = 0x01100013,
  kBayerGR16 = 0x0110002e, kBayerRG16 = 0x0110002f, kBayerGB16 = 0x01100030, kBayerBG16 = 0x01100031,
  kBayerBG10p = 0x010a0052, kBayerGB10p = 0x010a0054, kBayerGR10p = 0x010a0056, kBayerRG10p = 0x010a0058,
  kBayerBG12p = 0x010c0053, kBayerGB12p = 0x010c0055, kBayerGR12p = 0x010c0057, kBayerRG12p = 0x010c0059,
  kBayerGR12Packed = 0x010c002a, kBayerRG12Packed = 0x010c002b, kBayerGB12Packed = 0x010c002c,
  kBayerBG12Packed = 0x010c002d,
  kBayerGR10Packed = 0x010c0026, kBayerRG10Packed = 0x010c0027, kBayerGB10Packed = 0x010c0028,
  kBayerBG10Packed = 0x010c0029,
  kRGB8 = 0x02180014, kBGR8 = 0x02180015,
};

GenicamPixelLayout bayer(PixelFormat f, PixelPacking p, int bits) { return {f, p, bits, false}; }

}  // namespace

std::optional<GenicamPixelLayout> genicamPixelLayout(uint32_t pfnc) {
  using P = PixelPacking;
  using F = PixelFormat;
  switch (pfnc) {
    case kBayerRG8: return bayer(F::BayerRggb8, P::Bits8, 8);
    case kBayerGR8: return bayer(F::BayerGrbg8, P::Bits8, 8);
    case kBayerGB8: return bayer(F::BayerGbrg8, P::Bits8, 8);
    case kBayerBG8: return bayer(F::BayerBggr8, P::Bits8, 8);
    case kBayerRG10: return bayer(F::BayerRggb8, P::Unpacked16, 10);
    case kBayerGR10: return bayer(F::BayerGrbg8, P::Unpacked16, 10);
    case kBayerGB10: return bayer(F::BayerGbrg8, P::Unpacked16, 10);
    case kBayerBG10: return bayer(F::BayerBggr8, P::Unpacked16, 10);
    case kBayerRG12: return bayer(F::BayerRggb8, P::Unpacked16, 12);
    case kBayerGR12: return bayer(F::BayerGrbg8, P::Unpacked16, 12);
    case kBayerGB12: return bayer(F::BayerGbrg8, P::Unpacked16, 12);
    case kBayerBG12: return bayer(F::BayerBggr8, P::Unpacked16, 12);
    case kBayerRG16: return bayer(F::BayerRggb8, P::Unpacked16, 16);
    case kBayerGR16: return bayer(F::BayerGrbg8, P::Unpacked16, 16);
    case kBayerGB16: return bayer(F::BayerGbrg8, P::Unpacked16, 16);
    case kBayerBG16: return bayer(F::BayerBggr8, P::Unpacked16, 16);
    case kBayerRG10p: return bayer(F::BayerRggb8, P::Pfnc10p, 10);
    case kBayerGR10p: return bayer(F::BayerGrbg8, P::Pfnc10p, 10);
    case kBayerGB10p: return bayer(F::BayerGbrg8, P::Pfnc10p, 10);
    case kBayerBG10p: return bayer(F::BayerBggr8, P::Pfnc10p, 10);
    case kBayerRG12p: return bayer(F::BayerRggb8, P::Pfnc12p, 12);
    case kBayerGR12p: return bayer(F::BayerGrbg8, P::Pfnc12p, 12);
    case kBayerGB12p: return bayer(F::BayerGbrg8, P::Pfnc12p, 12);
    case kBayerBG12p: return bayer(F::BayerBggr8, P::Pfnc12p, 12);
    case kBayerRG10Packed: return bayer(F::BayerRggb8, P::GigePacked, 10);
    case kBayerGR10Packed: return bayer(F::BayerGrbg8, P::GigePacked, 10);
    case kBayerGB10Packed: return bayer(F::BayerGbrg8, P::GigePacked, 10);
    case kBayerBG10Packed: return bayer(F::BayerBggr8, P::GigePacked, 10);
    case kBayerRG12Packed: return bayer(F::BayerRggb8, P::GigePacked, 12);
    case kBayerGR12Packed: return bayer(F::BayerGrbg8, P::GigePacked, 12);
    case kBayerGB12Packed: return bayer(F::BayerGbrg8, P::GigePacked, 12);
    case kBayerBG12Packed: return bayer(F::BayerBggr8, P::GigePacked, 12);
    case kRGB8: return GenicamPixelLayout{F::Bgr8, P::Bits8, 8, true};
    case kBGR8: return GenicamPixelLayout{F::Bgr8, P::Bits8, 8, false};
    default: return std::nullopt;
  }
}

bool isMonoPixelFormat(uint32_t pfnc) {
  switch (pfnc) {
    case 0x01080001:  // Mono8
    case 0x01080002:  // Mono8s
    case 0x01100003:  // Mono10
    case 0x010c0004:  // Mono10Packed
    case 0x01100005:  // Mono12
    case 0x010c0006:  // Mono12Packed
    case 0x01100025:  // Mono14
    case 0x01100007:  // Mono16
    case 0x010a0046:  // Mono10p
    case 0x010c0047:  // Mono12p
      return true;
    default:
      return false;
  }
}

int genicamFormatPreference(uint32_t pfnc) {
  const auto l = genicamPixelLayout(pfnc);
  if (!l) return 0;
  if (l->format == PixelFormat::Bgr8) return 1;  // 3x the bandwidth of a mosaic
  if (l->packing == PixelPacking::Bits8) return 4;
  if (l->packing == PixelPacking::Unpacked16) return 2;
  return 3;  // packed: 1.5 bytes a pixel
}

std::string unusablePixelFormatReason(uint32_t pfnc, const std::string& name) {
  if (isMonoPixelFormat(pfnc) || name.rfind("Mono", 0) == 0)
    return "pixel format " + name +
           " is monochrome: dotvision needs color (a Bayer mosaic or RGB) to tell the teams' and "
           "robots' color patterns apart; set PixelFormat=BayerRG8 (or the camera's Bayer layout)";
  return "pixel format " + name +
         " is not supported (use a Bayer format: BayerRG8/GR8/GB8/BG8, their 10/12-bit variants, "
         "or RGB8/BGR8)";
}

size_t genicamImageBytes(const GenicamPixelLayout& l, int width, int height) {
  if (width <= 0 || height <= 0) return 0;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  // A leader may claim any 32-bit size: saturate rather than let n * 10
  // wrap to a small number that a short payload would pass.
  if (n > std::numeric_limits<size_t>::max() / 16) return std::numeric_limits<size_t>::max();
  if (l.format == PixelFormat::Bgr8) return 3 * n;
  switch (l.packing) {
    case PixelPacking::Bits8: return n;
    case PixelPacking::Unpacked16: return 2 * n;
    case PixelPacking::GigePacked:
    case PixelPacking::Pfnc12p: return (n * 3 + 1) / 2;
    case PixelPacking::Pfnc10p: return (n * 10 + 7) / 8;
  }
  return n;
}

namespace {

void reduceUnpacked16(const uint8_t* src, size_t n, int bits, uint8_t* dst) {
  const int shift = bits - 8;
  for (size_t i = 0; i < n; ++i) {
    const unsigned v = src[2 * i] | (unsigned(src[2 * i + 1]) << 8);
    const unsigned r = v >> shift;
    dst[i] = static_cast<uint8_t>(r > 255 ? 255 : r);
  }
}

void reduceGigePacked(const uint8_t* src, size_t n, uint8_t* dst) {
  // Byte 0 holds pixel 0's high 8 bits, byte 2 pixel 1's; byte 1 the low bits.
  size_t i = 0;
  for (; i + 1 < n; i += 2, src += 3) {
    dst[i] = src[0];
    dst[i + 1] = src[2];
  }
  if (i < n) dst[i] = src[0];
}

void reduce12p(const uint8_t* src, size_t n, uint8_t* dst) {
  // p0 = b0 | (b1 & 0xf) << 8, p1 = b1 >> 4 | b2 << 4; keep bits 11..4.
  size_t i = 0;
  for (; i + 1 < n; i += 2, src += 3) {
    dst[i] = static_cast<uint8_t>((src[0] >> 4) | (src[1] << 4));
    dst[i + 1] = src[2];
  }
  if (i < n) dst[i] = static_cast<uint8_t>((src[0] >> 4) | (src[1] << 4));
}

void reduce10p(const uint8_t* src, size_t n, uint8_t* dst) {
  // A little-endian bit stream of 10-bit samples; keep bits 9..2 of each.
  for (size_t i = 0; i < n; ++i) {
    const size_t bit = i * 10;
    const size_t byte = bit / 8;
    const unsigned shift = bit % 8;
    const unsigned v = (src[byte] | (unsigned(src[byte + 1]) << 8)) >> shift;
    dst[i] = static_cast<uint8_t>((v & 0x3ff) >> 2);
  }
}

}  // namespace

bool convertGenicamImage(const uint8_t* data, size_t size, int width, int height,
                         const GenicamPixelLayout& layout, cv::Mat& out) {
  if (width <= 0 || height <= 0 || size < genicamImageBytes(layout, width, height)) return false;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  if (layout.format == PixelFormat::Bgr8) {
    out.create(height, width, CV_8UC3);
    const cv::Mat src(height, width, CV_8UC3, const_cast<uint8_t*>(data));
    if (layout.rgb_order)
      cv::cvtColor(src, out, cv::COLOR_RGB2BGR);
    else
      src.copyTo(out);
    return true;
  }
  out.create(height, width, CV_8UC1);
  uint8_t* dst = out.ptr<uint8_t>();  // create() gives a continuous matrix
  switch (layout.packing) {
    case PixelPacking::Bits8: std::memcpy(dst, data, n); break;
    case PixelPacking::Unpacked16: reduceUnpacked16(data, n, layout.bits, dst); break;
    case PixelPacking::GigePacked: reduceGigePacked(data, n, dst); break;
    case PixelPacking::Pfnc12p: reduce12p(data, n, dst); break;
    case PixelPacking::Pfnc10p: reduce10p(data, n, dst); break;
  }
  return true;
}

}  // namespace dv

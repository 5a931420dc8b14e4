// GenICam pixel formats reduced to the Frame's 8-bit Bayer mosaic or BGR.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

#include "camera/genicam_pixels.h"

namespace dv {
namespace {

constexpr uint32_t kBayerRG8 = 0x01080009, kBayerGB12 = 0x01100012, kBayerBG10 = 0x0110000f,
                   kBayerRG12Packed = 0x010c002b, kBayerGR10Packed = 0x010c0026, kBayerBG12p = 0x010c0053,
                   kBayerRG10p = 0x010a0058, kRGB8 = 0x02180014, kBGR8 = 0x02180015, kMono8 = 0x01080001,
                   kMono12 = 0x01100005;

// 12-bit test samples: every value's high 8 bits differ from its neighbours'.
std::vector<unsigned> samples(int n, int bits) {
  std::vector<unsigned> v(n);
  for (int i = 0; i < n; ++i) v[i] = (i * 2654435761u >> 7) & ((1u << bits) - 1);
  return v;
}

cv::Mat convert(uint32_t pfnc, const std::vector<uint8_t>& bytes, int w, int h) {
  const auto layout = genicamPixelLayout(pfnc);
  EXPECT_TRUE(layout.has_value());
  cv::Mat out;
  EXPECT_TRUE(convertGenicamImage(bytes.data(), bytes.size(), w, h, *layout, out));
  return out;
}

void expectHighBits(const cv::Mat& out, const std::vector<unsigned>& v, int bits) {
  ASSERT_EQ(out.type(), CV_8UC1);
  for (size_t i = 0; i < v.size(); ++i) ASSERT_EQ(out.ptr<uint8_t>()[i], v[i] >> (bits - 8)) << "pixel " << i;
}

TEST(GenicamPixelsTest, BayerLayoutComesFromTheFormat) {
  EXPECT_EQ(genicamPixelLayout(0x01080009)->format, PixelFormat::BayerRggb8);
  EXPECT_EQ(genicamPixelLayout(0x01080008)->format, PixelFormat::BayerGrbg8);
  EXPECT_EQ(genicamPixelLayout(0x0108000a)->format, PixelFormat::BayerGbrg8);
  EXPECT_EQ(genicamPixelLayout(0x0108000b)->format, PixelFormat::BayerBggr8);
  EXPECT_EQ(genicamPixelLayout(kBayerGB12)->format, PixelFormat::BayerGbrg8);
  EXPECT_EQ(genicamPixelLayout(kBayerBG12p)->format, PixelFormat::BayerBggr8);
  EXPECT_EQ(genicamPixelLayout(kRGB8)->format, PixelFormat::Bgr8);
}

TEST(GenicamPixelsTest, MonoIsRefusedWithAReason) {
  EXPECT_FALSE(genicamPixelLayout(kMono8));
  EXPECT_TRUE(isMonoPixelFormat(kMono8));
  EXPECT_TRUE(isMonoPixelFormat(kMono12));
  EXPECT_FALSE(isMonoPixelFormat(kBayerRG8));
  EXPECT_EQ(genicamFormatPreference(kMono8), 0);
  EXPECT_GT(genicamFormatPreference(kBayerRG8), genicamFormatPreference(kBayerGB12));
  EXPECT_GT(genicamFormatPreference(kBayerGB12), genicamFormatPreference(kRGB8));
  EXPECT_NE(unusablePixelFormatReason(kMono8, "Mono8").find("monochrome"), std::string::npos);
  EXPECT_NE(unusablePixelFormatReason(0x02200017, "YUV422").find("not supported"), std::string::npos);
}

TEST(GenicamPixelsTest, EightBitBayerIsCopied) {
  std::vector<uint8_t> bytes(6 * 4);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(i * 37);
  const cv::Mat out = convert(kBayerRG8, bytes, 6, 4);
  ASSERT_EQ(out.rows, 4);
  ASSERT_EQ(out.cols, 6);
  EXPECT_EQ(0, std::memcmp(out.ptr<uint8_t>(), bytes.data(), bytes.size()));
}

TEST(GenicamPixelsTest, UnpackedTenAndTwelveBitsKeepTheHighEight) {
  for (auto [pfnc, bits] : {std::pair{kBayerGB12, 12}, std::pair{kBayerBG10, 10}}) {
    const auto v = samples(8 * 3, bits);
    std::vector<uint8_t> bytes;
    for (unsigned s : v) bytes.push_back(s & 0xff), bytes.push_back(s >> 8);
    expectHighBits(convert(pfnc, bytes, 8, 3), v, bits);
  }
}

TEST(GenicamPixelsTest, GigePackedKeepsTheHighEight) {
  for (auto [pfnc, bits] : {std::pair{kBayerRG12Packed, 12}, std::pair{kBayerGR10Packed, 10}}) {
    const auto v = samples(6 * 2, bits);
    std::vector<uint8_t> bytes;
    const int low = bits - 8;  // low bits of each pixel, in byte 1's two nibbles
    for (size_t i = 0; i < v.size(); i += 2) {
      bytes.push_back(v[i] >> low);
      bytes.push_back((v[i] & ((1 << low) - 1)) | ((v[i + 1] & ((1 << low) - 1)) << 4));
      bytes.push_back(v[i + 1] >> low);
    }
    expectHighBits(convert(pfnc, bytes, 6, 2), v, bits);
  }
}

TEST(GenicamPixelsTest, PfncTwelvePKeepsTheHighEight) {
  const auto v = samples(4 * 2, 12);
  std::vector<uint8_t> bytes;
  for (size_t i = 0; i < v.size(); i += 2) {
    bytes.push_back(v[i] & 0xff);
    bytes.push_back((v[i] >> 8) | ((v[i + 1] & 0xf) << 4));
    bytes.push_back(v[i + 1] >> 4);
  }
  expectHighBits(convert(kBayerBG12p, bytes, 4, 2), v, 12);
}

TEST(GenicamPixelsTest, PfncTenPKeepsTheHighEight) {
  const auto v = samples(8 * 2, 10);
  std::vector<uint8_t> bytes((v.size() * 10 + 7) / 8, 0);
  for (size_t i = 0; i < v.size(); ++i)  // a little-endian bit stream
    for (int b = 0; b < 10; ++b)
      if (v[i] >> b & 1) bytes[(i * 10 + b) / 8] |= static_cast<uint8_t>(1 << ((i * 10 + b) % 8));
  expectHighBits(convert(kBayerRG10p, bytes, 8, 2), v, 10);
}

TEST(GenicamPixelsTest, RgbIsSwappedToBgrAndBgrCopied) {
  const std::vector<uint8_t> rgb = {1, 2, 3, 4, 5, 6};
  const cv::Mat a = convert(kRGB8, rgb, 2, 1);
  ASSERT_EQ(a.type(), CV_8UC3);
  EXPECT_EQ(std::vector<uint8_t>(a.ptr<uint8_t>(), a.ptr<uint8_t>() + 6), (std::vector<uint8_t>{3, 2, 1, 6, 5, 4}));
  const cv::Mat b = convert(kBGR8, rgb, 2, 1);
  EXPECT_EQ(std::vector<uint8_t>(b.ptr<uint8_t>(), b.ptr<uint8_t>() + 6), rgb);
}

TEST(GenicamPixelsTest, ShortBufferIsRejectedAndTheOutputBufferIsReused) {
  const auto layout = *genicamPixelLayout(kBayerRG12Packed);
  std::vector<uint8_t> bytes(genicamImageBytes(layout, 8, 8));
  cv::Mat out;
  EXPECT_FALSE(convertGenicamImage(bytes.data(), bytes.size() - 1, 8, 8, layout, out));
  ASSERT_TRUE(convertGenicamImage(bytes.data(), bytes.size(), 8, 8, layout, out));
  const uint8_t* first = out.ptr<uint8_t>();
  ASSERT_TRUE(convertGenicamImage(bytes.data(), bytes.size(), 8, 8, layout, out));
  EXPECT_EQ(out.ptr<uint8_t>(), first) << "no new allocation for the same size";
}

// A buffer's leader may claim any width and height. 859019674 x 2147418113
// pixels of 10p need 2^64 + 4 bits: computed in 64 bits that wrapped to one
// byte, so a 16-byte payload passed the size check and was read as a huge image.
TEST(GenicamPixelsTest, AClaimedSizeWhoseByteCountWouldWrapIsRefused) {
  const auto layout = *genicamPixelLayout(kBayerRG10p);
  EXPECT_EQ(genicamImageBytes(layout, 859019674, 2147418113), std::numeric_limits<size_t>::max());
  std::vector<uint8_t> bytes(16);
  cv::Mat out;
  EXPECT_FALSE(convertGenicamImage(bytes.data(), bytes.size(), 859019674, 2147418113, layout, out));
  EXPECT_FALSE(convertGenicamImage(bytes.data(), bytes.size(), -4, -4, layout, out));
  EXPECT_EQ(genicamImageBytes(layout, -4, 4), 0u);
}

}  // namespace
}  // namespace dv

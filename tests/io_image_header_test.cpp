// Image headers are read before decoding: the claimed size of every format
// the frame sources take, and a frame claiming too many pixels skipped with
// a reason instead of a decoder allocating them.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "frame_count.h"
#include "io/frame_source.h"
#include "io/image_decode.h"
#include "io/image_header.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

std::vector<unsigned char> encoded(const std::string& ext, int w, int h, int channels) {
  cv::Mat m(h, w, channels == 1 ? CV_8UC1 : CV_8UC3, cv::Scalar(40, 90, 200));
  std::vector<unsigned char> bytes;
  EXPECT_TRUE(cv::imencode(ext, m, bytes)) << ext;
  return bytes;
}

TEST(ImageHeader, ReadsTheSizeOfEveryFormat) {
  for (const char* ext : {".png", ".jpg", ".pgm", ".ppm", ".bmp", ".tif"}) {
    const int channels = std::string(ext) == ".pgm" ? 1 : 3;
    const auto bytes = encoded(ext, 37, 21, channels);
    const auto size = claimedImageSize(bytes.data(), bytes.size());
    ASSERT_TRUE(size.has_value()) << ext;
    EXPECT_EQ(size->width, 37) << ext;
    EXPECT_EQ(size->height, 21) << ext;
  }
  const std::string text = "P5 # a comment\n# another\n 640\t480\n255\n";
  const auto pgm = claimedImageSize(reinterpret_cast<const unsigned char*>(text.data()), text.size());
  ASSERT_TRUE(pgm.has_value());
  EXPECT_EQ(pgm->width, 640);
  EXPECT_EQ(pgm->height, 480);
  const std::string other = "GIF89a....";
  EXPECT_FALSE(claimedImageSize(reinterpret_cast<const unsigned char*>(other.data()), other.size()));
}

TEST(ImageHeader, LimitDoesNotOverflow) {
  EXPECT_FALSE(tooManyPixels({2448, 2048}));
  EXPECT_FALSE(tooManyPixels({8192, 8192}));
  EXPECT_TRUE(tooManyPixels({8193, 8192}));
  EXPECT_TRUE(tooManyPixels({0xffffffffLL, 0xffffffffLL}));
  EXPECT_TRUE(tooManyPixels({int64_t(1) << 40, int64_t(1) << 40}));
  EXPECT_FALSE(tooManyPixels({0, 0xffffffffLL}));
}

class ImageHeaderSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dv_imghdr_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // The folder read through a frame source: the indices of the frames it
  // delivered; `src` keeps the source for its skips.
  std::vector<uint32_t> readAll(std::unique_ptr<FrameSource>& src) const {
    src = openFrameSource(dir_.string(), {});
    Frame f;
    std::vector<uint32_t> delivered;
    while (src->next(f)) delivered.push_back(f.index);
    return delivered;
  }
  void write(const std::string& name, const std::vector<unsigned char>& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                       std::streamsize(bytes.size()));
  }
  fs::path dir_;
};

void putBig32(unsigned char* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (24 - 8 * i));
}

// Each file (PNG, PGM, BMP, JPEG, TIFF) claims 40000x40000 pixels (1.6 Gpx, about 4.8 GB decoded); the
// valid frame after them is still delivered.
TEST_F(ImageHeaderSourceTest, HugeClaimedSizeIsSkippedWithTheSize) {
  auto png = encoded(".png", 8, 8, 3);
  putBig32(png.data() + 16, 40000);
  putBig32(png.data() + 20, 40000);
  putBig32(png.data() + 29, uint32_t(::crc32(0, png.data() + 12, 17)));  // IHDR's CRC stays valid
  write("a_0.png", png);
  const std::string pgm_text = "P5\n40000 40000\n255\n" + std::string(64, 'x');
  write("a_1.pgm", std::vector<unsigned char>(pgm_text.begin(), pgm_text.end()));
  auto bmp = encoded(".bmp", 8, 8, 3);
  for (int i = 0; i < 4; ++i) bmp[18 + i] = bmp[22 + i] = static_cast<unsigned char>((40000 >> (8 * i)) & 0xff);
  write("a_2.bmp", bmp);
  auto jpg = encoded(".jpg", 8, 8, 3);
  bool patched = false;
  for (size_t i = 2; i + 9 < jpg.size() && !patched; ++i) {
    if (jpg[i] == 0xff && jpg[i + 1] == 0xc0) {
      jpg[i + 5] = jpg[i + 7] = 40000 >> 8;
      jpg[i + 6] = jpg[i + 8] = 40000 & 0xff;
      patched = true;
    }
  }
  ASSERT_TRUE(patched);
  write("a_3.jpg", jpg);
  auto tif = encoded(".tif", 8, 8, 3);
  ASSERT_EQ(tif[0], 'I');  // OpenCV writes little-endian TIFF
  const size_t ifd = tif[4] | tif[5] << 8 | tif[6] << 16 | size_t(tif[7]) << 24;
  int sizes = 0;
  for (size_t i = 0, n = tif[ifd] | tif[ifd + 1] << 8; i < n; ++i) {
    unsigned char* e = tif.data() + ifd + 2 + 12 * i;
    if ((e[0] | e[1] << 8) != 256 && (e[0] | e[1] << 8) != 257) continue;
    e[8] = 40000 & 0xff, e[9] = 40000 >> 8, e[10] = e[11] = 0;  // SHORT or LONG alike
    ++sizes;
  }
  ASSERT_EQ(sizes, 2);
  write("a_4.tif", tif);
  write("a_5.png", encoded(".png", 8, 8, 3));

  std::unique_ptr<FrameSource> src;
  const std::vector<uint32_t> delivered = readAll(src);
  EXPECT_EQ(delivered, std::vector<uint32_t>{5});
  ASSERT_EQ(src->skipped().size(), 5u);
  for (const auto& skip : src->skipped()) {
    EXPECT_NE(skip.reason.find("claims 40000x40000 pixels"), std::string::npos) << skip.name << ": " << skip.reason;
    EXPECT_NE(skip.reason.find("64 Mpx"), std::string::npos) << skip.reason;
  }
}


// Found by fuzz_image_decode: "P6 01281%637200 5700" and "P6 012882#63700
// 02057": OpenCV's PNM reader takes the character that ends a number,
// whatever it is, so it read 1281 x 637200 and 12882 x 63700 pixels of 16
// bits (4.9 GB each) where a reading by the format's rules saw no size or
// 12882 x 6. The header is read as the decoder reads it and refused for its
// size; a header that is not decimal numbers is refused as damaged; the
// frame after each still comes.
TEST_F(ImageHeaderSourceTest, PnmHeaderIsReadAsTheDecoderReadsIt) {
  const std::string percent = "P6 01281%637200 5700\x83" "012890";
  const std::string hash = "P6 012882#63700 02057\x83!01oooooooooooooooooo\n6\n20";
  const std::string damaged = "P6 01281 %637200 5700\n";
  write("a_0.pgm", std::vector<unsigned char>(percent.begin(), percent.end()));
  write("a_1.pgm", std::vector<unsigned char>(hash.begin(), hash.end()));
  write("a_2.ppm", std::vector<unsigned char>(damaged.begin(), damaged.end()));
  write("a_3.png", encoded(".png", 8, 8, 3));
  std::unique_ptr<FrameSource> src;
  const std::vector<uint32_t> delivered = readAll(src);
  EXPECT_EQ(delivered, std::vector<uint32_t>{3});
  ASSERT_EQ(src->skipped().size(), 3u);
  const char* expected[] = {"claims 1281x637200 pixels", "claims 12882x63700 pixels", "damaged PNM header"};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NE(src->skipped()[i].reason.find(expected[i]), std::string::npos) << src->skipped()[i].reason;
    EXPECT_NE(src->skipped()[i].name.find("a_" + std::to_string(i)), std::string::npos) << src->skipped()[i].name;
  }
}


// Each format's size is read as OpenCV's decoder reads it, so that no file
// reaches a decoder with a size other than the one checked.
TEST(ImageHeader, ReadsTheSizeTheDecoderReads) {
  // libjpeg steps over bytes before a marker: a frame header after three
  // stray bytes (once a 56 s fill of 900 Mpx under the fuzzer) still counts.
  auto jpg = encoded(".jpg", 8, 8, 3);
  size_t sof = 0;
  for (size_t i = 2; i + 9 < jpg.size() && !sof; ++i)
    if (jpg[i] == 0xff && jpg[i + 1] == 0xc0) sof = i;
  ASSERT_GT(sof, 0u);
  jpg[sof + 5] = jpg[sof + 7] = 30000 >> 8;
  jpg[sof + 6] = jpg[sof + 8] = 30000 & 0xff;
  jpg.insert(jpg.begin() + long(sof), {0x00, 0x12, 0x34});
  auto size = claimedImageSize(jpg.data(), jpg.size());
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->width, 30000);
  EXPECT_EQ(size->height, 30000);

  // An OS/2 bitmap's 12-byte header holds 16-bit sizes (read as 32-bit
  // ones, 640 x 480 was 31 million pixels wide).
  std::vector<unsigned char> bmp(64, 0);
  bmp[0] = 'B', bmp[1] = 'M', bmp[14] = 12;
  bmp[18] = 640 & 0xff, bmp[19] = 640 >> 8, bmp[20] = 480 & 0xff, bmp[21] = 480 >> 8;
  bmp[22] = 1, bmp[24] = 24;
  size = claimedImageSize(bmp.data(), bmp.size());
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->width, 640);
  EXPECT_EQ(size->height, 480);

  // TIFF: libtiff takes any integer type for the sizes. A signed LONG width
  // is read; one of a type not read (RATIONAL, 5) leaves the size unread.
  auto tif = encoded(".tif", 8, 8, 3);
  ASSERT_EQ(tif[0], 'I');
  const size_t ifd = tif[4] | tif[5] << 8 | tif[6] << 16 | size_t(tif[7]) << 24;
  unsigned char* width_entry = nullptr;
  for (size_t i = 0, n = tif[ifd] | tif[ifd + 1] << 8; i < n; ++i) {
    unsigned char* e = tif.data() + ifd + 2 + 12 * i;
    if ((e[0] | e[1] << 8) == 256) width_entry = e;
  }
  ASSERT_NE(width_entry, nullptr);
  width_entry[2] = 9, width_entry[3] = 0;  // SLONG
  width_entry[8] = 40000 & 0xff, width_entry[9] = 40000 >> 8, width_entry[10] = width_entry[11] = 0;
  size = claimedImageSize(tif.data(), tif.size());
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->width, 40000);
  width_entry[2] = 5;
  EXPECT_FALSE(claimedImageSize(tif.data(), tif.size()).has_value());
}

// A calibration image goes the same checked way as a frame: a header
// claiming too many pixels is named with the file, never decoded.
TEST_F(ImageHeaderSourceTest, CalibrationImageIsCheckedLikeAFrame) {
  const std::string pgm = "P5\n40000 40000\n255\n" + std::string(64, 'x');
  write("field.pgm", std::vector<unsigned char>(pgm.begin(), pgm.end()));
  const std::string path = (dir_ / "field.pgm").string();
  try {
    readImageFile(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("claims 40000x40000"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("field.pgm"), std::string::npos) << e.what();
  }
  write("good.png", encoded(".png", 8, 6, 3));
  const cv::Mat good = readImageFile((dir_ / "good.png").string());
  EXPECT_EQ(good.cols, 8);
  EXPECT_EQ(good.rows, 6);
}

// Found by fuzz_image_decode: a file with the DICOM marker at byte 128 made
// OpenCV hand it to its DICOM reader, which aborted the whole process on
// the damaged data. Only the formats the sources take reach a decoder.
TEST_F(ImageHeaderSourceTest, OtherFormatsAndDicomNeverReachADecoder) {
  static const char kCrash[] =
      "\x50\x34\x23\x35\x32\x31\x36\x20\xff\xff\x5f\x30\x00\x3c\x18\xa3\x01\x31\x00\x4d\x7e\x4c\x00\x00"
      "\x00\x00\x30\x20\x32\x34\xe8\x1d\xfe\x00\x59\xa6\x6a\x95\x27\x1d\xff\xd8\xd8\xd8\x00\x00\x00\x00"
      "\x00\x18\xa3\x01\x30\x00\xff\x01\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00"
      "\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49"
      "\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x49\x8e\x8e\x8e\x8e\x8e\x8e\x8e\x8e\x8e\x8e\x8e\x8e\x8e"
      "\x8e\x8e\x8e\x8e\x8e\x8e\xff\xff\x44\x49\x43\x4d\x00";
  const auto* b = reinterpret_cast<const unsigned char*>(kCrash);
  write("a_0.pgm", std::vector<unsigned char>(b, b + sizeof kCrash - 1));
  const std::string webp = "RIFF\x24\0\0\0WEBPVP8 " + std::string(40, 'x');
  write("a_1.png", std::vector<unsigned char>(webp.begin(), webp.end()));
  write("a_2.tif", encoded(".tiff", 8, 8, 3));
  std::unique_ptr<FrameSource> src;
  const std::vector<uint32_t> delivered = readAll(src);
  EXPECT_EQ(delivered, std::vector<uint32_t>{2});  // the TIFF
  ASSERT_EQ(src->skipped().size(), 2u);
  for (const auto& skip : src->skipped())
    EXPECT_NE(skip.reason.find("not a PNG, JPEG, PNM, BMP or TIFF image"), std::string::npos) << skip.reason;
  EXPECT_STREQ(acceptedImageFormat(b, sizeof kCrash - 1), nullptr);
}


// A damaged header in a format the sources take: skipped with the project's
// reason, and OpenCV's own "imdecode_(...): can't read header" line (which
// its decoders write to std::cerr themselves) is not printed.
TEST_F(ImageHeaderSourceTest, DamagedHeaderIsSkippedWithoutTheDecodersOwnLines) {
  const std::string pgm = "P5\n8 x\n255\n" + std::string(64, 'x');
  write("a_0.pgm", std::vector<unsigned char>(pgm.begin(), pgm.end()));
  auto bmp = encoded(".bmp", 8, 8, 3);
  for (int i = 2; i < 6; ++i) bmp[size_t(i)] = 0;  // the file size field
  for (int i = 10; i < 14; ++i) bmp[size_t(i)] = 0xff;  // the pixel offset
  write("a_1.bmp", bmp);
  write("a_2.png", encoded(".png", 8, 8, 3));
  auto src = openFrameSource(dir_.string(), {});
  const test::FramesRead read = test::readAllFrames(*src);
  EXPECT_EQ(read.frames, 1);
  EXPECT_EQ(read.printed, "");
  EXPECT_EQ(src->skipped().size(), 2u);
}

}  // namespace
}  // namespace dv

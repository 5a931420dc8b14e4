// Frame sources: formats, order, timestamps, and bad frames that are skipped
// with a reason while the source goes on.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "core/error.h"
#include "frame_count.h"
#include "io/frame_source.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

class FrameSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("dv_src_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // A small color image whose top-left pixel encodes `tag` (B channel).
  void writeColor(const std::string& name, int tag, int w = 32, int h = 24) const {
    cv::Mat m(h, w, CV_8UC3, cv::Scalar(10, 20, 30));
    m.at<cv::Vec3b>(0, 0) = cv::Vec3b(static_cast<uchar>(tag), 0, 0);
    ASSERT_TRUE(cv::imwrite(path(name), m));
  }
  fs::path dir_;
};

TEST_F(FrameSourceTest, SinglePngIsBgr) {
  writeColor("a.png", 7);
  auto src = openFrameSource(path("a.png"), {});
  Frame f;
  ASSERT_TRUE(src->next(f));
  EXPECT_EQ(f.format, PixelFormat::Bgr8);
  EXPECT_EQ(f.image.type(), CV_8UC3);
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], 7);
  EXPECT_EQ(f.index, 0u);
  EXPECT_DOUBLE_EQ(f.t_capture, 0);
  EXPECT_FALSE(src->next(f));
  EXPECT_TRUE(src->skipped().empty());
}

TEST_F(FrameSourceTest, GrayPgmIsBayerInTheChosenPattern) {
  cv::Mat raw(16, 16, CV_8UC1, cv::Scalar(99));
  ASSERT_TRUE(cv::imwrite(path("raw.pgm"), raw));
  FrameSourceOptions opt;
  opt.bayer = bayerFormatFromName("GBRG", "--bayer");
  auto src = openFrameSource(path("raw.pgm"), opt);
  Frame f;
  ASSERT_TRUE(src->next(f));
  EXPECT_EQ(f.format, PixelFormat::BayerGbrg8);
  EXPECT_EQ(f.image.type(), CV_8UC1);
  EXPECT_EQ(f.image.at<uchar>(3, 3), 99);
  EXPECT_THROW(bayerFormatFromName("rgbg", "--bayer"), InputError);
}

TEST_F(FrameSourceTest, DirectoryIsSortedByNameWithSequenceTimestamps) {
  writeColor("f_002.png", 2);
  writeColor("f_000.png", 0);
  writeColor("f_001.jpg", 1);
  std::ofstream(path("notes.txt")) << "not an image";
  std::ofstream(path("truth.jsonl")) << "{}";
  FrameSourceOptions opt;
  opt.fps = 50;
  auto src = openFrameSource(dir_.string(), opt);
  EXPECT_EQ(src->expectedCount(), 3);
  Frame f;
  std::vector<std::string> names;
  std::vector<double> times;
  while (src->next(f)) {
    names.push_back(fs::path(f.name).filename().string());
    times.push_back(f.t_capture);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"f_000.png", "f_001.jpg", "f_002.png"}));
  EXPECT_EQ(times, (std::vector<double>{0.0, 0.02, 0.04}));
}

TEST_F(FrameSourceTest, SynthDirectoryYieldsOneCamerasFramesOncePerFrame) {
  writeColor("frame_0_00000.png", 0);
  cv::imwrite(path("frame_0_00000.pgm"), cv::Mat(24, 32, CV_8UC1, cv::Scalar(5)));
  cv::imwrite(path("frame_0_00001.pgm"), cv::Mat(24, 32, CV_8UC1, cv::Scalar(6)));
  cv::imwrite(path("frame_1_00000.pgm"), cv::Mat(24, 32, CV_8UC1, cv::Scalar(7)));
  FrameSourceOptions opt;
  opt.scene_camera = 0;
  auto src = openFrameSource(dir_.string(), opt);
  Frame f;
  std::vector<std::string> names;
  while (src->next(f)) names.push_back(fs::path(f.name).filename().string());
  EXPECT_EQ(names, (std::vector<std::string>{"frame_0_00000.pgm", "frame_0_00001.pgm"}));
  opt.scene_camera = 1;
  EXPECT_EQ(openFrameSource(dir_.string(), opt)->expectedCount(), 1);
  opt.scene_camera = 2;
  EXPECT_THROW(openFrameSource(dir_.string(), opt), InputError);
  // Without the option every image counts.
  EXPECT_EQ(openFrameSource(dir_.string(), {})->expectedCount(), 4);
  // Names of other kinds are not filtered.
  EXPECT_EQ(selectSceneCamera({"a.png", "b.png"}, 3).size(), 2u);
}

TEST_F(FrameSourceTest, GlobSelectsMatchingImages) {
  writeColor("cam0_1.png", 1);
  writeColor("cam0_0.png", 0);
  writeColor("cam1_0.png", 9);
  auto src = openFrameSource(path("cam0_*.png"), {});
  Frame f;
  int n = 0;
  while (src->next(f)) {
    EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], n);
    ++n;
  }
  EXPECT_EQ(n, 2);
  EXPECT_THROW(openFrameSource(path("nothing_*.png"), {}), InputError);
}

TEST_F(FrameSourceTest, TruncatedAndCorruptFilesAreSkippedAndTheSourceGoesOn) {
  writeColor("a_0.png", 0);
  writeColor("a_1.png", 1);
  writeColor("a_2.jpg", 2);
  writeColor("a_3.png", 3);
  writeColor("a_4.png", 4);
  fs::resize_file(path("a_1.png"), fs::file_size(path("a_1.png")) / 2);
  fs::resize_file(path("a_2.jpg"), fs::file_size(path("a_2.jpg")) - 10);
  std::ofstream(path("a_3.png"), std::ios::trunc) << "garbage, not a PNG";
  auto src = openFrameSource(dir_.string(), {});
  Frame f;
  std::vector<uint32_t> indices;
  while (src->next(f)) indices.push_back(f.index);
  EXPECT_EQ(indices, (std::vector<uint32_t>{0, 4}));
  ASSERT_EQ(src->skipped().size(), 3u);
  EXPECT_NE(src->skipped()[0].name.find("a_1.png"), std::string::npos);
  EXPECT_NE(src->skipped()[0].reason.find("truncated PNG"), std::string::npos);
  EXPECT_NE(src->skipped()[1].reason.find("truncated JPEG"), std::string::npos);
  EXPECT_NE(src->skipped()[2].name.find("a_3.png"), std::string::npos);
  EXPECT_FALSE(src->skipped()[2].reason.empty());
}

TEST_F(FrameSourceTest, SixteenBitImagesAreSkipped) {
  cv::Mat deep(8, 8, CV_16UC1, cv::Scalar(1000));
  ASSERT_TRUE(cv::imwrite(path("deep.png"), deep));
  auto src = openFrameSource(path("deep.png"), {});
  Frame f;
  EXPECT_FALSE(src->next(f));
  ASSERT_EQ(src->skipped().size(), 1u);
  EXPECT_NE(src->skipped()[0].reason.find("8-bit"), std::string::npos);
}

TEST_F(FrameSourceTest, MissingPathsAndUnreadableVideosAreInputErrors) {
  EXPECT_THROW(openFrameSource(path("missing.png"), {}), InputError);
  fs::create_directories(path("empty"));
  EXPECT_THROW(openFrameSource(path("empty"), {}), InputError);
  std::ofstream(path("clip.mp4")) << "this is not a video";
  try {
    openFrameSource(path("clip.mp4"), {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("clip.mp4"), std::string::npos) << e.what();
  }
  FrameSourceOptions bad;
  bad.fps = 0;
  writeColor("a.png", 1);
  EXPECT_THROW(openFrameSource(path("a.png"), bad), InputError);
}

TEST_F(FrameSourceTest, VideoFramesComeInOrderWithContainerTimes) {
  cv::VideoWriter writer(path("clip.avi"), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'),
                         25, cv::Size(64, 48));
  if (!writer.isOpened()) GTEST_SKIP() << "no FFmpeg video writer in this OpenCV build";
  for (int i = 0; i < 5; ++i) writer.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar(i * 40, 0, 0)));
  writer.release();
  auto src = openFrameSource(path("clip.avi"), {});
  Frame f;
  int n = 0;
  while (src->next(f)) {
    EXPECT_EQ(f.format, PixelFormat::Bgr8);
    EXPECT_EQ(f.image.size(), cv::Size(64, 48));
    EXPECT_NEAR(f.t_capture, n / 25.0, 1e-3);
    EXPECT_NEAR(f.image.at<cv::Vec3b>(10, 10)[0], n * 40, 12);
    ++n;
  }
  EXPECT_EQ(n, 5);
}

TEST_F(FrameSourceTest, UndecodableLastVideoFrameIsCountedAsSkipped) {
  cv::VideoWriter writer(path("clip.avi"), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'),
                         25, cv::Size(64, 48));
  if (!writer.isOpened()) GTEST_SKIP() << "no FFmpeg video writer in this OpenCV build";
  for (int i = 0; i < 6; ++i) writer.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar(i * 40, 0, 0)));
  writer.release();
  // Wipe the last frame's JPEG data (from its start-of-image marker on).
  std::string bytes;
  {
    std::ifstream in(path("clip.avi"), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const size_t last = bytes.rfind("\xff\xd8\xff");
  ASSERT_NE(last, std::string::npos);
  const size_t end = bytes.find("idx1", last);
  ASSERT_NE(end, std::string::npos);
  std::fill(bytes.begin() + long(last), bytes.begin() + long(end) - 8, '\0');
  std::ofstream(path("clip.avi"), std::ios::binary | std::ios::trunc) << bytes;

  auto src = openFrameSource(path("clip.avi"), {});
  Frame f;
  int n = 0;
  while (src->next(f)) ++n;
  EXPECT_EQ(n, 5);
  ASSERT_EQ(src->skipped().size(), 1u);
  EXPECT_NE(src->skipped()[0].name.find("clip.avi#5"), std::string::npos) << src->skipped()[0].name;
  EXPECT_NE(src->skipped()[0].reason.find("5 of 6"), std::string::npos) << src->skipped()[0].reason;
}

TEST_F(FrameSourceTest, DanglingLinkInAFolderIsSkippedWithAReason) {
  writeColor("a_0.png", 1);
  fs::create_symlink(path("gone.png"), path("a_1.png"));
  writeColor("a_2.png", 3);
  auto src = openFrameSource(dir_.string(), {});
  Frame f;
  int n = 0;
  while (src->next(f)) ++n;
  EXPECT_EQ(n, 2);
  ASSERT_EQ(src->skipped().size(), 1u);
  EXPECT_NE(src->skipped()[0].name.find("a_1.png"), std::string::npos);
  EXPECT_NE(src->skipped()[0].reason.find("dangling symbolic link"), std::string::npos)
      << src->skipped()[0].reason;
  EXPECT_NE(src->skipped()[0].reason.find("gone.png"), std::string::npos) << src->skipped()[0].reason;
}

// A bit flipped in a PNG's image data: skipped with our reason, and the
// decoder library prints nothing of its own ("libpng error: ...").
TEST_F(FrameSourceTest, DamagedPngIsSkippedWithoutTheDecodersOwnLines) {
  writeColor("a_0.png", 0);
  std::string bytes;
  {
    std::ifstream in(path("a_0.png"), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const size_t idat = bytes.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  bytes[idat + 6] = char(bytes[idat + 6] ^ 0x55);
  std::ofstream(path("a_0.png"), std::ios::binary | std::ios::trunc) << bytes;
  writeColor("a_1.png", 1);
  auto src = openFrameSource(dir_.string(), {});
  const test::FramesRead read = test::readAllFrames(*src);
  EXPECT_EQ(read.frames, 1);
  EXPECT_EQ(read.printed, "");
  ASSERT_EQ(src->skipped().size(), 1u);
  EXPECT_NE(src->skipped()[0].reason.find("IDAT chunk at byte"), std::string::npos) << src->skipped()[0].reason;
}

}  // namespace
}  // namespace dv

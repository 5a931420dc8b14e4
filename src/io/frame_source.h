#pragma once
// Where camera frames come from: still images, a directory or glob of
// images, a video file, or (in the app) the synthetic scene. A source hands
// out frames one by one into a caller-owned Frame whose pixel buffer is
// reused; a frame that cannot be read becomes a skip record and the source
// moves on to the next one, so one bad file never ends a run.
#include <opencv2/core/mat.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace dv {

// Layout of Frame::image.
enum class PixelFormat {
  Bgr8,        // 3 channels, OpenCV's BGR order (decoded PNG/JPEG, video)
  BayerRggb8,  // 1 channel raw sensor mosaic, top-left 2x2 = R G / G B
  BayerGrbg8,
  BayerGbrg8,
  BayerBggr8,
};

const char* pixelFormatName(PixelFormat f);
// "rggb", "grbg", "gbrg", "bggr" (case-insensitive) -> Bayer format.
// Throws InputError naming `source` for anything else.
PixelFormat bayerFormatFromName(const std::string& text, const std::string& source);

struct Frame {
  cv::Mat image;            // Bgr8 or one Bayer layout; video reuses the buffer
  PixelFormat format = PixelFormat::Bgr8;
  // s. Live cameras: Unix time at the end of the exposure (the camera's
  // clock mapped to the host's, else the arrival time). Files and videos:
  // FrameSourceOptions::time_origin + sequence time (index / fps or the
  // container's time), so a run anchored at its start carries Unix time.
  double t_capture = 0;
  double t_capture_camera = -1;  // s on the camera's own clock; < 0: none
  double t_arrival = 0;          // Unix s when the host received it (0: not live)
  uint32_t index = 0;       // position in the source, counting every input incl. skipped ones
  std::string name;         // file name or "video.mp4#17", for messages
};

// A frame the source (or the run loop) could not use, and why.
struct SkipRecord {
  std::string name;
  std::string reason;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Fills `f` with the next good frame. Returns false at the end of the
  // source. Bad inputs met on the way are appended to skipped().
  virtual bool next(Frame& f) = 0;
  // What this source is, for messages ("images in /tmp/scene", "video x.mp4").
  virtual std::string describe() const = 0;
  // Number of frames the source will yield in total, when known (else -1).
  virtual long expectedCount() const { return -1; }

  const std::vector<SkipRecord>& skipped() const { return skipped_; }
  void recordSkip(std::string name, std::string reason) {
    skipped_.push_back({std::move(name), std::move(reason)});
  }

 private:
  std::vector<SkipRecord> skipped_;
};

// A frame's number, capture time (Unix s) and layout as a camera delivered
// it (a raw dump's frame_times.csv, src/io/frame_times.h).
struct FrameTiming {
  uint32_t index = 0;
  double t_capture = 0;
  PixelFormat format = PixelFormat::Bgr8;
};

struct FrameSourceOptions {
  double fps = 60;  // sequence timestamps: index / fps
  double time_origin = 0;  // s added to every sequence time (run: Unix time at start)
  PixelFormat bayer = PixelFormat::BayerRggb8;  // meaning of single-channel images
  // For a directory written by `dotvision synth` (frame_<cam>_<NNNNN>.pgm/.png):
  // take only this camera's frames, one file per frame (the raw .pgm where
  // both exist). -1 or a directory without such names: every image.
  long scene_camera = -1;
};

// A fixed list of image files, read in the given order. Color images
// (PNG/JPEG/...) become Bgr8; 8-bit single-channel images (PGM, gray PNG) are
// taken as raw Bayer mosaics in options.bayer. 16-bit images, unreadable or
// truncated files are skipped with a reason.
class ImageSequenceSource : public FrameSource {
 public:
  ImageSequenceSource(std::vector<std::string> paths, FrameSourceOptions options,
                      std::string description);
  bool next(Frame& f) override;
  std::string describe() const override { return description_; }
  long expectedCount() const override { return static_cast<long>(paths_.size()); }
  const std::vector<std::string>& paths() const { return paths_; }
  // Frame numbers, capture times and layouts by file name (a raw dump's
  // frame_times.csv); files listed there take these instead of index / fps.
  void setTimings(std::map<std::string, FrameTiming> timings) { timings_ = std::move(timings); }

 private:
  std::vector<std::string> paths_;
  FrameSourceOptions options_;
  std::string description_;
  size_t cursor_ = 0;
  std::vector<unsigned char> file_bytes_;  // reused read buffer
  std::map<std::string, FrameTiming> timings_;
};

// A video file decoded by OpenCV (FFmpeg backend). Timestamps come from the
// container (CAP_PROP_POS_MSEC); where it reports none, index / fps.
class VideoSource : public FrameSource {
 public:
  VideoSource(const std::string& path, FrameSourceOptions options);
  ~VideoSource() override;
  bool next(Frame& f) override;
  std::string describe() const override { return "video " + path_; }
  long expectedCount() const override { return frame_count_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
  FrameSourceOptions options_;
  long frame_count_ = -1;
  uint32_t index_ = 0;
};

// True for names that look like still images we can read (.png .jpg .jpeg
// .pgm .ppm .pnm .bmp .tif .tiff), case-insensitive.
bool isImageFileName(const std::string& path);
// True for common video containers (.mp4 .avi .mkv .mov .webm .m4v .mpg .mpeg).
bool isVideoFileName(const std::string& path);

// Applies FrameSourceOptions::scene_camera to a sorted list of image paths.
std::vector<std::string> selectSceneCamera(const std::vector<std::string>& sorted_paths, long camera);

// Opens `spec`: an image file, a directory (its image files, sorted by name),
// a glob pattern with * ? or [..] (matching image files, sorted by name), or a
// video file. Throws InputError naming `spec` when it does not exist, matches
// nothing, or cannot be opened.
std::unique_ptr<FrameSource> openFrameSource(const std::string& spec,
                                             const FrameSourceOptions& options);

}  // namespace dv

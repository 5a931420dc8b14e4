#include "io/frame_source.h"
#include "io/frame_times.h"

#include <glob.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/error.h"
#include "io/image_header.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool endsWith(const std::vector<unsigned char>& bytes, size_t size, const unsigned char* tail,
              size_t n) {
  return size >= n && std::equal(tail, tail + n, bytes.begin() + static_cast<long>(size - n));
}

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
std::string truncationReason(const std::vector<unsigned char>& bytes, size_t size) {
  static const unsigned char kPngMagic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static const unsigned char kPngEnd[8] = {'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  if (size >= 8 && std::equal(kPngMagic, kPngMagic + 8, bytes.begin())) {
    if (!endsWith(bytes, size, kPngEnd, 8)) return "truncated PNG (no IEND chunk at the end)";
    return pngChunkDamage(bytes.data(), size);
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

bool readFileInto(const std::string& path, std::vector<unsigned char>& buffer, size_t& size) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (end < 0) return false;
  in.seekg(0, std::ios::beg);
  size = static_cast<size_t>(end);
  if (buffer.size() < size) buffer.resize(size);
  in.read(reinterpret_cast<char*>(buffer.data()), static_cast<std::streamsize>(size));
  return static_cast<size_t>(in.gcount()) == size;
}

// A link to nothing stays in the list, so that reading it records a skip
// instead of the frame vanishing without a word.
bool isImageOrDanglingLink(const fs::path& p) {
  std::error_code ec;
  if (!isImageFileName(p.string())) return false;
  if (fs::is_regular_file(p, ec)) return true;
  return fs::is_symlink(fs::symlink_status(p, ec)) && !fs::exists(p, ec);
}

std::vector<std::string> imagesInDirectory(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (isImageOrDanglingLink(entry.path())) out.push_back(entry.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> imagesMatchingGlob(const std::string& pattern) {
  std::vector<std::string> out;
  glob_t g{};
  if (::glob(pattern.c_str(), 0, nullptr, &g) == 0) {
    for (size_t i = 0; i < g.gl_pathc; ++i) {
      std::string p = g.gl_pathv[i];
      if (isImageOrDanglingLink(p)) out.push_back(std::move(p));
    }
  }
  globfree(&g);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

const char* pixelFormatName(PixelFormat f) {
  switch (f) {
    case PixelFormat::Bgr8: return "bgr8";
    case PixelFormat::BayerRggb8: return "bayer-rggb8";
    case PixelFormat::BayerGrbg8: return "bayer-grbg8";
    case PixelFormat::BayerGbrg8: return "bayer-gbrg8";
    case PixelFormat::BayerBggr8: return "bayer-bggr8";
  }
  return "unknown";
}

PixelFormat bayerFormatFromName(const std::string& text, const std::string& source) {
  std::string t = text;
  std::transform(t.begin(), t.end(), t.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (t == "rggb") return PixelFormat::BayerRggb8;
  if (t == "grbg") return PixelFormat::BayerGrbg8;
  if (t == "gbrg") return PixelFormat::BayerGbrg8;
  if (t == "bggr") return PixelFormat::BayerBggr8;
  throw InputError(source, "unknown Bayer pattern '" + text + "' (expected rggb, grbg, gbrg or bggr)");
}

bool isImageFileName(const std::string& path) {
  static const char* kExt[] = {".png", ".jpg", ".jpeg", ".pgm", ".ppm", ".pnm", ".bmp", ".tif", ".tiff"};
  const std::string ext = lowerExtension(path);
  return std::any_of(std::begin(kExt), std::end(kExt), [&](const char* e) { return ext == e; });
}

bool isVideoFileName(const std::string& path) {
  static const char* kExt[] = {".mp4", ".avi", ".mkv", ".mov", ".webm", ".m4v", ".mpg", ".mpeg"};
  const std::string ext = lowerExtension(path);
  return std::any_of(std::begin(kExt), std::end(kExt), [&](const char* e) { return ext == e; });
}

// ---- still images ----

ImageSequenceSource::ImageSequenceSource(std::vector<std::string> paths, FrameSourceOptions options,
                                         std::string description)
    : paths_(std::move(paths)), options_(options), description_(std::move(description)) {}

bool ImageSequenceSource::next(Frame& f) {
  while (cursor_ < paths_.size()) {
    const uint32_t index = static_cast<uint32_t>(cursor_);
    const std::string& path = paths_[cursor_++];
    size_t size = 0;
    if (!readFileInto(path, file_bytes_, size)) {
      std::error_code ec;
      if (fs::is_symlink(fs::symlink_status(path, ec)) && !fs::exists(path, ec)) {
        recordSkip(path, "dangling symbolic link (to " + fs::read_symlink(path, ec).string() + ")");
      } else {
        recordSkip(path, "cannot read the file");
      }
      continue;
    }
    if (size == 0) {
      recordSkip(path, "empty file");
      continue;
    }
    if (std::string why = truncationReason(file_bytes_, size); !why.empty()) {
      recordSkip(path, why);
      continue;
    }
    const char* format = acceptedImageFormat(file_bytes_.data(), size);
    if (!format) {
      recordSkip(path, "not a PNG, JPEG, PNM, BMP or TIFF image (by its first bytes)");
      continue;
    }
    const auto claimed = claimedImageSize(file_bytes_.data(), size);
    // A PNM size this check cannot read never reaches the decoder, which
    // would allocate whatever it reads.
    if (!claimed && std::strcmp(format, "PNM") == 0) {
      recordSkip(path, "damaged PNM header: the width and height are not decimal numbers");
      continue;
    }
    if (claimed && tooManyPixels(*claimed)) {
      recordSkip(path, "the header claims " + std::to_string(claimed->width) + "x" +
                           std::to_string(claimed->height) + " pixels, above the limit of " +
                           std::to_string(kMaxImagePixels >> 20) + " Mpx");
      continue;
    }
    const cv::Mat bytes(1, static_cast<int>(size), CV_8UC1, file_bytes_.data());
    // A fresh Mat: on failure OpenCV leaves a passed-in target untouched,
    // which would hand out the previous image as this one.
    cv::Mat decoded;
    try {
      const MutedStdCerr quiet;
      decoded = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception& e) {
      recordSkip(path, std::string("cannot decode the image: ") + e.what());
      continue;
    }
    if (decoded.empty()) {
      recordSkip(path, "not a readable image (corrupt or unsupported format)");
      continue;
    }
    if (decoded.depth() != CV_8U) {
      recordSkip(path, "unsupported pixel depth (only 8-bit images are accepted)");
      continue;
    }
    switch (decoded.channels()) {
      case 1:
        f.image = decoded;
        f.format = options_.bayer;
        break;
      case 3:
        f.image = decoded;
        f.format = PixelFormat::Bgr8;
        break;
      case 4:
        cv::cvtColor(decoded, f.image, cv::COLOR_BGRA2BGR);
        f.format = PixelFormat::Bgr8;
        break;
      default:
        recordSkip(path, "unsupported channel count " + std::to_string(decoded.channels()));
        continue;
    }
    f.index = index;
    f.t_capture = options_.time_origin + index / options_.fps;
    if (!timings_.empty()) {
      const auto it = timings_.find(fs::path(path).filename().string());
      if (it != timings_.end()) {
        f.index = it->second.index;
        f.t_capture = it->second.t_capture;
        if (f.format != PixelFormat::Bgr8 && it->second.format != PixelFormat::Bgr8) f.format = it->second.format;
      }
    }
    f.name = path;
    return true;
  }
  return false;
}

// ---- video ----

struct VideoSource::Impl {
  cv::VideoCapture capture;
};

VideoSource::VideoSource(const std::string& path, FrameSourceOptions options)
    : impl_(std::make_unique<Impl>()), path_(path), options_(options) {
  if (!fs::exists(path)) throw InputError(path, "no such video file");
  bool opened = false;
  try {
    opened = impl_->capture.open(path, cv::CAP_FFMPEG);
  } catch (const cv::Exception&) {
    opened = false;
  }
  if (!opened || !impl_->capture.isOpened())
    throw InputError(path, "cannot open as a video (not a video file, or no decoder for it)");
  const double count = impl_->capture.get(cv::CAP_PROP_FRAME_COUNT);
  if (count > 0) frame_count_ = static_cast<long>(count);
}

VideoSource::~VideoSource() = default;

bool VideoSource::next(Frame& f) {
  bool ok = false;
  try {
    ok = impl_->capture.read(f.image);
  } catch (const cv::Exception& e) {
    recordSkip(path_ + "#" + std::to_string(index_), std::string("decoder error: ") + e.what());
    return false;
  }
  if (!ok || f.image.empty()) {
    // The container's count includes a last frame that did not decode.
    if (frame_count_ > 0 && index_ < static_cast<uint32_t>(frame_count_))
      recordSkip(path_ + "#" + std::to_string(index_),
                 "the video ended early (" + std::to_string(index_) + " of " +
                     std::to_string(frame_count_) + " frames decoded)");
    return false;
  }
  if (f.image.channels() == 1) {
    f.format = options_.bayer;
  } else {
    f.format = PixelFormat::Bgr8;
  }
  const double ms = impl_->capture.get(cv::CAP_PROP_POS_MSEC);
  f.index = index_;
  f.t_capture = options_.time_origin + ((ms > 0 || index_ == 0) ? ms / 1000.0 : index_ / options_.fps);
  f.name = path_ + "#" + std::to_string(index_);
  ++index_;
  return true;
}

// ---- factory ----

std::vector<std::string> selectSceneCamera(const std::vector<std::string>& sorted_paths, long camera) {
  if (camera < 0) return sorted_paths;
  // frame_<cam>_<n>: parsed by hand to keep <regex> out of this file.
  auto parse = [](const std::string& path, long& cam, long& n) {
    const std::string stem = fs::path(path).stem().string();
    if (stem.rfind("frame_", 0) != 0) return false;
    const size_t sep = stem.find('_', 6);
    if (sep == std::string::npos || sep == 6 || sep + 1 >= stem.size()) return false;
    const std::string a = stem.substr(6, sep - 6), b = stem.substr(sep + 1);
    auto digits = [](const std::string& t) {
      return !t.empty() && std::all_of(t.begin(), t.end(), [](unsigned char c) { return std::isdigit(c); });
    };
    if (!digits(a) || !digits(b)) return false;
    cam = std::stol(a);
    n = std::stol(b);
    return true;
  };
  std::vector<std::string> out;
  long last_n = -1;
  bool any_scene_name = false;
  for (const std::string& p : sorted_paths) {
    long cam = 0, n = 0;
    if (!parse(p, cam, n)) continue;
    any_scene_name = true;
    if (cam != camera) continue;
    if (n == last_n) {  // same frame as .pgm and .png: keep the raw mosaic
      if (lowerExtension(p) == ".pgm") out.back() = p;
      continue;
    }
    out.push_back(p);
    last_n = n;
  }
  return any_scene_name ? out : sorted_paths;
}

std::unique_ptr<FrameSource> openFrameSource(const std::string& spec,
                                             const FrameSourceOptions& options) {
  if (!(options.fps > 0)) throw InputError("command line", "--fps must be positive");
  const bool is_glob = spec.find_first_of("*?[") != std::string::npos && !fs::exists(spec);
  if (is_glob) {
    auto paths = imagesMatchingGlob(spec);
    if (paths.empty()) throw InputError(spec, "the pattern matches no image files");
    return std::make_unique<ImageSequenceSource>(std::move(paths), options, "images matching " + spec);
  }
  std::error_code ec;
  if (!fs::exists(spec, ec)) throw InputError(spec, "no such file or directory");
  if (fs::is_directory(spec, ec)) {
    auto paths = imagesInDirectory(spec);
    if (paths.empty()) throw InputError(spec, "the directory holds no image files");
    paths = selectSceneCamera(paths, options.scene_camera);
    if (paths.empty())
      throw InputError(spec, "the directory holds no frames of camera " + std::to_string(options.scene_camera));
    auto source = std::make_unique<ImageSequenceSource>(std::move(paths), options, "images in " + spec);
    source->setTimings(readFrameTimes(spec));  // a raw dump: the frames' own numbers and times
    return source;
  }
  if (isImageFileName(spec)) {
    return std::make_unique<ImageSequenceSource>(std::vector<std::string>{spec}, options,
                                                 "image " + spec);
  }
  // Anything else is handed to the video decoder, which names it if it fails.
  return std::make_unique<VideoSource>(spec, options);
}

}  // namespace dv

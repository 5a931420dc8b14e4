#include "io/frame_source.h"
#include "io/frame_times.h"

#include <glob.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/error.h"
#include "io/image_decode.h"

namespace dv {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

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
    // A fresh Mat: on failure OpenCV leaves a passed-in target untouched,
    // which would hand out the previous image as this one.
    cv::Mat decoded;
    if (std::string why = decodeImageBytes(file_bytes_.data(), size, decoded); !why.empty()) {
      recordSkip(path, why);
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

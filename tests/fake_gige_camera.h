#pragma once
// Aravis's own fake GigE Vision camera, in this process, on 127.0.0.1: the
// real GVCP control and GVSP stream protocols over loopback. Its frames are
// a known pattern (fakePattern) so a test can check every byte received.
//
// A GigE Vision camera listens on UDP port 3956 of its interface, so only
// one fake camera can run on loopback at a time: the object holds a
// machine-wide lock (a file lock in the temp directory) while it lives, and
// tests in parallel processes take turns.
#include <arv.h>
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace dv::test {

// Frame `seq` of the pattern: bytes 0..3 are seq (little endian), the rest
// a xorshift stream seeded by it.
inline void fakePattern(uint8_t* dst, size_t n, uint32_t seq) {
  uint32_t x = seq * 2654435761u + 1;
  for (size_t i = 0; i < n; ++i) {
    if (i < 4) {
      dst[i] = static_cast<uint8_t>(seq >> (8 * i));
      continue;
    }
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    dst[i] = static_cast<uint8_t>(x >> 24);
  }
}
inline uint32_t fakePatternSeq(const uint8_t* p) { return p[0] | p[1] << 8 | p[2] << 16 | uint32_t(p[3]) << 24; }

// Aravis's fake camera description with more PixelFormat entries (the
// GenICam value and name of each), written to `path`; for formats Aravis's
// own description does not offer.
inline bool writeFakeGenicamWithFormats(const std::string& path,
                                        const std::vector<std::pair<std::string, uint32_t>>& formats) {
  ArvFakeCamera* reference = arv_fake_camera_new("xml");
  size_t size = 0;
  const char* xml = arv_fake_camera_get_genicam_xml(reference, &size);
  std::string text(xml ? xml : "", xml ? size : 0);
  g_object_unref(reference);
  const size_t at = text.find("<pValue>PixelFormatRegister</pValue>");
  if (at == std::string::npos) return false;
  std::string entries;
  for (const auto& [name, value] : formats)
    entries += "<EnumEntry Name=\"" + name + "\" NameSpace=\"Standard\"><Value>" + std::to_string(value) +
               "</Value></EnumEntry>\n";
  text.insert(at, entries);
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  return std::fclose(f) == 0 && ok;
}

class FakeGigeCamera {
 public:
  // cheap_fill: every frame is the same pattern but for its seq bytes (a
  // memcpy, for benchmarks at full rate); else each frame is its own.
  // genicam_file: another description of the camera ("" = Aravis's own).
  explicit FakeGigeCamera(std::string serial, int sensor_width = 2448, int sensor_height = 2048,
                          bool cheap_fill = false, std::string genicam_file = "")
      : serial_(std::move(serial)), sensor_width_(sensor_width), sensor_height_(sensor_height),
        cheap_fill_(cheap_fill), genicam_file_(std::move(genicam_file)) {
    const auto lock_path = std::filesystem::temp_directory_path() / "dotvision_fake_gige_camera.lock";
    lock_fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT, 0666);
    if (lock_fd_ >= 0) ::flock(lock_fd_, LOCK_EX);
    start();
  }
  ~FakeGigeCamera() {
    stop();
    if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
  }
  FakeGigeCamera(const FakeGigeCamera&) = delete;
  FakeGigeCamera& operator=(const FakeGigeCamera&) = delete;

  // The camera appears (again, with the same serial) / disappears, as a
  // camera powered on / unplugged.
  void start() {
    if (camera_) return;
    // Aravis's fake does not notice when its control socket cannot bind
    // (and would then answer discovery while another program answers
    // control), so the port is checked first.
    if (!gvcpPortFree()) return;
    camera_ = arv_gv_fake_camera_new_full("127.0.0.1", serial_.c_str(),
                                          genicam_file_.empty() ? nullptr : genicam_file_.c_str());
    if (!arv_gv_fake_camera_is_running(camera_)) return;
    ArvFakeCamera* fake = arv_gv_fake_camera_get_fake_camera(camera_);
    // The sensor is 2048x2048 unless these registers are written.
    arv_fake_camera_write_register(fake, ARV_FAKE_CAMERA_REGISTER_SENSOR_WIDTH, sensor_width_);
    arv_fake_camera_write_register(fake, ARV_FAKE_CAMERA_REGISTER_SENSOR_HEIGHT, sensor_height_);
    arv_fake_camera_set_fill_pattern(fake, &FakeGigeCamera::fill, this);
  }
  void stop() { g_clear_object(&camera_); }

  // False where the fake cannot bind 127.0.0.1:3956 (another GigE camera
  // program on loopback, no loopback interface).
  bool running() const { return camera_ && arv_gv_fake_camera_is_running(camera_); }
  const std::string& serial() const { return serial_; }
  std::string deviceId() const { return "Aravis-Fake-" + serial_; }
  uint32_t framesWritten() const { return seq_.load(); }
  // Streams these images (one byte per pixel, the camera's size) in turn
  // instead of the pattern; call before anyone opens the stream.
  void streamImages(std::vector<std::vector<uint8_t>> images) { images_ = std::move(images); }
  static bool gvcpPortFree() {
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    if (fd < 0) return false;
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(3956);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    const bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
    ::close(fd);
    return ok;
  }

  // Drops this share of the stream's packets on the way out (Aravis's own
  // "gvsp-lost-ratio", per thousand), as a congested link would.
  void losePackets(double per_thousand) {
    GParamSpec* p = g_object_class_find_property(G_OBJECT_GET_CLASS(camera_), "gvsp-lost-ratio");
    if (!p) return;
    if (G_PARAM_SPEC_VALUE_TYPE(p) == G_TYPE_DOUBLE) g_object_set(camera_, "gvsp-lost-ratio", per_thousand / 1000.0, nullptr);
    else g_object_set(camera_, "gvsp-lost-ratio", static_cast<guint>(per_thousand), nullptr);
  }

  // The camera's registers, read and written in memory (not over the network).
  uint32_t reg(uint32_t address) const {
    guint32 v = 0;
    arv_fake_camera_read_register(arv_gv_fake_camera_get_fake_camera(camera_), address, &v);
    return v;
  }
  void setReg(uint32_t address, uint32_t value) {
    arv_fake_camera_write_register(arv_gv_fake_camera_get_fake_camera(camera_), address, value);
  }

 private:
  // Called by the fake camera's thread for each frame. The GigE fake sends
  // the whole payload from the buffer's data whatever the buffer's
  // received size says, so writing the bytes is enough here.
  static void fill(ArvBuffer* buffer, void* self_ptr, guint32, guint32, ArvPixelFormat format) {
    auto* self = static_cast<FakeGigeCamera*>(self_ptr);
    const size_t n = static_cast<size_t>(arv_buffer_get_image_width(buffer)) * arv_buffer_get_image_height(buffer) *
                     ARV_PIXEL_FORMAT_BIT_PER_PIXEL(format) / 8;
    auto* data = static_cast<uint8_t*>(const_cast<void*>(arv_buffer_get_data(buffer, nullptr)));
    const uint32_t seq = ++self->seq_;
    if (!self->images_.empty()) {
      const std::vector<uint8_t>& img = self->images_[(seq - 1) % self->images_.size()];
      if (img.size() == n) return static_cast<void>(std::memcpy(data, img.data(), n));
    }
    if (!self->cheap_fill_) return fakePattern(data, n, seq);
    if (self->fixed_.size() != n) {
      self->fixed_.resize(n);
      fakePattern(self->fixed_.data(), n, 0);
    }
    std::memcpy(data, self->fixed_.data(), n);
    for (size_t i = 0; i < 4 && i < n; ++i) data[i] = static_cast<uint8_t>(seq >> (8 * i));
  }

  std::string serial_;
  int sensor_width_, sensor_height_;
  bool cheap_fill_;
  std::string genicam_file_;
  std::vector<uint8_t> fixed_;  // the cheap fill's frame (fake camera thread only)
  std::vector<std::vector<uint8_t>> images_;  // streamImages
  int lock_fd_ = -1;
  ArvGvFakeCamera* camera_ = nullptr;
  std::atomic<uint32_t> seq_{0};
};

}  // namespace dv::test

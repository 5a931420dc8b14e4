#include "camera/genicam_source.h"

#include <arv.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <future>
#include <mutex>

#include "camera/camera_list.h"
#include "camera/clock_offset.h"
#include "camera/frame_id_gap.h"
#include "camera/genicam_defaults.h"
#include "camera/genicam_features.h"
#include "camera/genicam_pixels.h"
#include "camera/gvcp_probe.h"
#include "camera/receive_buffer.h"
#include "camera/aravis_error.h"
#include "core/error.h"

namespace dv {

namespace {

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
double unixSeconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

const char* bufferStatusText(ArvBufferStatus s) {
  switch (s) {
    case ARV_BUFFER_STATUS_TIMEOUT: return "timed out before all its packets came";
    case ARV_BUFFER_STATUS_MISSING_PACKETS: return "is missing packets";
    case ARV_BUFFER_STATUS_WRONG_PACKET_ID: return "has a packet with a wrong id";
    case ARV_BUFFER_STATUS_SIZE_MISMATCH: return "did not fit the buffer (payload size changed?)";
    case ARV_BUFFER_STATUS_ABORTED: return "was aborted";
    case ARV_BUFFER_STATUS_CLEARED: return "was cleared";
    case ARV_BUFFER_STATUS_FILLING: return "was still filling";
    default: return "has an unknown status";
  }
}

// Heartbeat thread of the device: the camera says we no longer control it.
void onControlLost(ArvDevice*, gpointer flag) { static_cast<std::atomic<bool>*>(flag)->store(true); }

std::atomic<bool> g_rmem_warned{false};  // the rmem_max cap is said once per process

}  // namespace

struct GenicamSource::Impl {
  GenicamOptions options;
  std::string spec;       // "genicam://ID" as given, for messages
  std::string device_id;  // Aravis device id, for reconnecting
  std::string camera_text = "camera";  // "Aravis Fake, serial GV01"

  ArvCamera* camera = nullptr;
  ArvStream* stream = nullptr;
  gulong control_lost_handler = 0;
  bool gige = false;
  std::string gige_ip;  // the camera's address, for quick probes
  bool streaming = false;

  bool lost = false;
  std::string lost_why;
  std::atomic<bool> control_lost{false};
  std::atomic<bool> interrupted{false};
  std::future<bool> probe;  // "does the camera still answer?" while frames stall
  double last_activity = 0;  // steady s of the last buffer or answered probe

  std::vector<CameraSetting> settings;  // all applied so far, replayed on reconnect
  ClockOffset clock;
  uint64_t last_frame_id = 0;
  uint32_t index = 0;
  std::atomic<uint64_t> frames{0}, skipped{0}, lost_frames{0};

  mutable std::mutex describe_mutex;
  std::string format_text;  // "BayerRG8 640x480"

  ArvDevice* device() const { return arv_camera_get_device(camera); }

  void open();
  void applyDefaults();
  std::vector<std::string> applyList(const std::vector<CameraSetting>& list);
  void updateFormatText();
  bool startStream(std::string& reason);  // reason without the spec
  void stopStream(bool camera_answers);
  void close(bool camera_answers);
  GrabStatus markLost(std::string reason, std::string& why);
  bool stalled(std::string& why);
  GrabStatus take(ArvBuffer* b, Frame& f, std::string& why);
  GrabStatus skip(uint64_t frame_id, const std::string& what, std::string& why);
};

void GenicamSource::Impl::open() {
  GError* error = nullptr;
  camera = arv_camera_new(device_id.c_str(), &error);
  if (!camera) throw InputError(spec, "cannot open camera " + device_id + ": " + takeErrorMessage(error));
  gige = arv_camera_is_gv_device(camera);
  ArvDevice* dev = device();
  gige_ip.clear();
  if (gige) {
    auto* address = arv_gv_device_get_device_address(ARV_GV_DEVICE(dev));
    if (address && G_IS_INET_SOCKET_ADDRESS(address)) {
      gchar* ip = g_inet_address_to_string(g_inet_socket_address_get_address(G_INET_SOCKET_ADDRESS(address)));
      gige_ip = ip ? ip : "";
      g_free(ip);
    }
  }
  arv_device_set_access_check_policy(dev, ARV_ACCESS_CHECK_POLICY_ENABLE);
  control_lost = false;
  control_lost_handler = g_signal_connect(dev, "control-lost", G_CALLBACK(onControlLost), &control_lost);
  const char* vendor = arv_camera_get_vendor_name(camera, nullptr);
  const char* model = arv_camera_get_model_name(camera, nullptr);
  const char* serial = arv_camera_get_device_serial_number(camera, nullptr);
  {
    std::lock_guard<std::mutex> lock(describe_mutex);
    camera_text = std::string(vendor ? vendor : "?") + " " + (model ? model : "?") + ", serial " +
                  (serial ? serial : "?");
  }
  applyDefaults();
}

void GenicamSource::Impl::applyDefaults() {
  const auto notes = applyGenicamDefaults(camera, options.max_fps, spec, camera_text);
  std::string joined;
  for (const auto& n : notes) joined += (joined.empty() ? "" : ", ") + n;
  spdlog::info("{}: {} start-up defaults: {}", spec, camera_text, joined);
  updateFormatText();
}

std::vector<std::string> GenicamSource::Impl::applyList(const std::vector<CameraSetting>& list) {
  std::vector<std::string> lines;
  bool frame_rate_given = false;
  for (const auto& s : list) {
    lines.push_back(setGenicamFeature(device(), s, spec, camera_text));
    frame_rate_given = frame_rate_given || s.name.find("FrameRate") != std::string::npos;
    const ArvPixelFormat pf = arv_camera_get_pixel_format(camera, nullptr);
    if (!genicamPixelLayout(pf)) {
      const char* name = arv_camera_get_pixel_format_as_string(camera, nullptr);
      throw InputError(spec, "camera setting " + s.name + "=" + s.value + " on " + camera_text + ": " +
                                 unusablePixelFormatReason(pf, name ? name : "?"));
    }
  }
  // A new size or format may change the fastest rate the camera can run.
  if (!list.empty() && !frame_rate_given) applyGenicamFrameRateDefault(camera, options.max_fps, spec);
  updateFormatText();
  return lines;
}

bool GenicamSource::Impl::startStream(std::string& reason) {
  GError* error = nullptr;
  if (gige) {
    // Aravis's packet-socket receive path does not see loopback traffic.
    auto* address = arv_gv_device_get_device_address(ARV_GV_DEVICE(device()));
    if (address && G_IS_INET_SOCKET_ADDRESS(address) &&
        g_inet_address_get_is_loopback(g_inet_socket_address_get_address(G_INET_SOCKET_ADDRESS(address))))
      arv_camera_gv_set_stream_options(camera, ARV_GV_STREAM_OPTION_PACKET_SOCKET_DISABLED);
  }
  stream = arv_camera_create_stream(camera, nullptr, nullptr, &error);
  if (!stream) {
    reason = "cannot open the stream of " + camera_text + ": " + takeErrorMessage(error);
    return false;
  }
  const guint payload = arv_camera_get_payload(camera, &error);
  if (error || payload == 0) {
    reason = "cannot read the payload size of " + camera_text + ": " + takeErrorMessage(error);
    stopStream(true);
    return false;
  }
  if (ARV_IS_GV_STREAM(stream)) {
    const size_t want = streamSocketBufferBytes(payload);
    g_object_set(stream, "socket-buffer", ARV_GV_STREAM_SOCKET_BUFFER_FIXED, "socket-buffer-size",
                 static_cast<int>(want), nullptr);
    const std::string capped = rmemCapMessage(spec, want, readRmemMax());
    if (!capped.empty() && !g_rmem_warned.exchange(true)) spdlog::warn("{}", capped);
  }
  for (int i = 0; i < std::max(options.buffers, 2); ++i) arv_stream_push_buffer(stream, arv_buffer_new(payload, nullptr));
  arv_camera_start_acquisition(camera, &error);
  if (error) {
    reason = camera_text + " does not start acquisition: " + takeErrorMessage(error);
    stopStream(true);
    return false;
  }
  streaming = true;
  last_activity = steadySeconds();
  return true;
}

void GenicamSource::Impl::updateFormatText() {
  gint x = 0, y = 0, w = 0, h = 0;
  arv_camera_get_region(camera, &x, &y, &w, &h, nullptr);
  const char* format = arv_camera_get_pixel_format_as_string(camera, nullptr);
  std::lock_guard<std::mutex> lock(describe_mutex);
  format_text = std::string(format ? format : "?") + " " + std::to_string(w) + "x" + std::to_string(h);
}

void GenicamSource::Impl::stopStream(bool camera_answers) {
  if (streaming && camera_answers) arv_camera_stop_acquisition(camera, nullptr);
  streaming = false;
  if (stream) g_clear_object(&stream);  // frees the buffers it holds
}

void GenicamSource::Impl::close(bool camera_answers) {
  if (probe.valid()) probe.wait();  // it uses the device
  probe = {};
  stopStream(camera_answers);
  if (camera) {
    if (control_lost_handler) g_signal_handler_disconnect(device(), control_lost_handler);
    control_lost_handler = 0;
    g_clear_object(&camera);  // the device goes with it (its heartbeat thread is joined)
  }
}

GrabStatus GenicamSource::Impl::markLost(std::string reason, std::string& why) {
  lost = true;
  lost_why = spec + ": " + std::move(reason);
  why = lost_why;
  return GrabStatus::Lost;
}

// No frame for stall_s: ask the camera in the background whether it still
// answers (losing control is reported by Aravis's heartbeat instead).
bool GenicamSource::Impl::stalled(std::string& why) {
  const double now = steadySeconds();
  if (probe.valid()) {
    if (probe.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
    const bool answers = probe.get();
    if (!answers) {
      char quiet[32];
      std::snprintf(quiet, sizeof quiet, "%.1f", now - last_activity);
      markLost(camera_text + " does not answer (no frame for " + quiet + " s)", why);
      return true;
    }
    last_activity = now;  // alive, only quiet (e.g. triggered)
    return false;
  }
  if (now - last_activity > options.stall_s) {
    ArvDevice* dev = device();
    const std::string ip = gige_ip;
    probe = std::async(std::launch::async, [dev, ip] {
      if (!ip.empty()) return gvcpCameraAnswers(ip);
      guint32 v = 0;  // USB3 Vision: the bootstrap registers start at 0
      return static_cast<bool>(arv_device_read_register(dev, 0, &v, nullptr));
    });
  }
  return false;
}

GrabStatus GenicamSource::Impl::skip(uint64_t frame_id, const std::string& what, std::string& why) {
  ++skipped;
  why = spec + ": frame " + std::to_string(frame_id) + " " + what;
  return GrabStatus::Skipped;
}

GrabStatus GenicamSource::Impl::take(ArvBuffer* b, Frame& f, std::string& why) {
  const double arrival = unixSeconds();
  last_activity = steadySeconds();
  f.index = index++;
  const uint64_t id = arv_buffer_get_frame_id(b);
  lost_frames += missedFrameIds(last_frame_id, id);
  last_frame_id = id;
  const ArvBufferStatus status = arv_buffer_get_status(b);
  if (status != ARV_BUFFER_STATUS_SUCCESS) return skip(id, bufferStatusText(status), why);
  const ArvBufferPayloadType type = arv_buffer_get_payload_type(b);
  if (type != ARV_BUFFER_PAYLOAD_TYPE_IMAGE && type != ARV_BUFFER_PAYLOAD_TYPE_EXTENDED_CHUNK_DATA &&
      type != ARV_BUFFER_PAYLOAD_TYPE_MULTIPART)
    return skip(id, "is not an image (payload type " + std::to_string(int(type)) + ")", why);
  const ArvPixelFormat pf = arv_buffer_get_image_pixel_format(b);
  const auto layout = genicamPixelLayout(pf);
  if (!layout) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%08x", static_cast<unsigned>(pf));
    return skip(id, std::string("has unusable pixel format ") + hex, why);
  }
  const int w = arv_buffer_get_image_width(b), h = arv_buffer_get_image_height(b);
  size_t size = 0;
  const auto* data = static_cast<const uint8_t*>(arv_buffer_get_image_data(b, &size));
  if (!data || !convertGenicamImage(data, size, w, h, *layout, f.image))
    return skip(id, "has " + std::to_string(size) + " bytes, " + std::to_string(w) + "x" + std::to_string(h) +
                        " needs " + std::to_string(genicamImageBytes(*layout, w, h)), why);
  f.format = layout->format;
  f.t_arrival = arrival;
  const guint64 camera_ns = arv_buffer_get_timestamp(b);
  if (camera_ns) {
    f.t_capture_camera = static_cast<double>(camera_ns) * 1e-9;
    f.t_capture = clock.map(f.t_capture_camera, arrival);
  } else {
    f.t_capture_camera = -1;
    f.t_capture = arrival;
  }
  // "genicam://ID#frame": assign/append reuse the string's capacity.
  char number[24];
  const auto end = std::to_chars(number, number + sizeof number, id).ptr;
  f.name.assign(spec);
  f.name.push_back('#');
  f.name.append(number, end);
  ++frames;
  return GrabStatus::Frame;
}

GenicamSource::GenicamSource(const std::string& id, GenicamOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->spec = "genicam://" + id;
  impl_->device_id = resolveGenicamId(id, impl_->spec);
  try {
    impl_->open();
  } catch (...) {
    impl_->close(true);
    throw;
  }
}

GenicamSource::~GenicamSource() { impl_->close(!impl_->lost); }

GrabStatus GenicamSource::grab(Frame& f, double timeout_s, std::string& why) {
  Impl& m = *impl_;
  if (m.lost) {
    why = m.lost_why;
    return GrabStatus::Lost;
  }
  if (!m.streaming) {
    std::string reason;
    if (!m.startStream(reason)) return m.markLost(reason, why);
  }
  const double deadline = steadySeconds() + std::max(timeout_s, 0.0);
  for (;;) {
    if (m.interrupted.exchange(false)) return GrabStatus::Timeout;
    if (m.control_lost)
      return m.markLost("lost control of " + m.camera_text + " (it restarted, or another application took it)", why);
    // Short slices so that interrupt() and the stall check are seen quickly.
    const double slice = std::clamp(deadline - steadySeconds(), 1e-6, 0.05);
    if (ArvBuffer* b = arv_stream_timeout_pop_buffer(m.stream, static_cast<guint64>(slice * 1e6))) {
      const GrabStatus s = m.take(b, f, why);
      arv_stream_push_buffer(m.stream, b);
      return s;
    }
    if (m.stalled(why)) return GrabStatus::Lost;
    if (steadySeconds() >= deadline) return GrabStatus::Timeout;
  }
}

bool GenicamSource::reconnect(std::string& why) {
  Impl& m = *impl_;
  // Closing a device that does not answer blocks for seconds (Aravis says
  // goodbye to it), so the old one is closed only once the camera is back.
  const bool back = (!m.gige_ip.empty() && gvcpCameraAnswers(m.gige_ip)) || genicamCameraPresent(m.device_id);
  if (!back) {
    why = m.spec + ": camera " + m.device_id + " is still gone (no answer, not found by discovery)";
    return false;
  }
  m.close(true);
  try {
    m.open();
    m.applyList(m.settings);
  } catch (const InputError& e) {
    why = e.what();
    m.close(true);
    return false;
  }
  m.lost = false;
  m.lost_why.clear();
  m.clock.reset();
  m.last_frame_id = 0;
  std::string reason;
  if (!m.startStream(reason)) {
    why = m.spec + ": " + reason;
    m.close(true);
    return false;
  }
  return true;
}

std::vector<std::string> GenicamSource::applySettings(const std::vector<CameraSetting>& settings) {
  Impl& m = *impl_;
  if (!m.camera) throw InputError(m.spec, "the camera is not connected; settings wait for reconnect");
  if (settings.empty()) return {};
  m.stopStream(true);  // size and format changes need a new stream; grab() restarts it
  auto lines = m.applyList(settings);
  m.settings.insert(m.settings.end(), settings.begin(), settings.end());
  return lines;
}

void GenicamSource::interrupt() { impl_->interrupted = true; }

std::string GenicamSource::describe() const {
  std::lock_guard<std::mutex> lock(impl_->describe_mutex);
  return impl_->spec + " (" + impl_->camera_text + (impl_->format_text.empty() ? "" : ", " + impl_->format_text) +
         ")";
}

SourceCounters GenicamSource::counters() const {
  return {impl_->frames.load(), impl_->skipped.load(), impl_->lost_frames.load()};
}

const std::string& GenicamSource::deviceId() const { return impl_->device_id; }

}  // namespace dv

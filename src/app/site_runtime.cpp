#include "app/site_runtime.h"


#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <thread>

#include "app/raw_dump.h"
#include "app/synthetic_camera.h"
#include "camera/open_camera.h"
#include "core/clock.h"
#include "core/error.h"
#include "net/geometry_publisher.h"

namespace dv::app {

namespace {

// As often as the publisher repeats the geometry (SSL-Vision: 3 s), so a
// restarted publisher has every camera back before its second publication.
constexpr auto kCalibrationResendInterval = std::chrono::seconds(3);
constexpr size_t kRawRingBytes = size_t{1} << 30;  // per camera: 10 s of 1224 x 1024, 3.4 s of 2448 x 2048 at 60 fps

std::string cameraName(const SiteCamera& c) { return "camera " + std::to_string(c.id); }

std::unique_ptr<CameraSource> openSiteSource(const SiteCamera& cam, std::vector<std::string>& report) {
  if (isSyntheticSpec(cam.source)) return std::make_unique<SyntheticCamera>(cam.source, cam.fps_given ? cam.fps : 0);
  CameraSourceOptions so;
  so.files.fps = cam.fps;
  so.files.bayer = bayerFormatFromName(cam.bayer, "camera " + std::to_string(cam.id) + " bayer");
  so.files.scene_camera = cam.id;
  so.files.time_origin = unixSeconds();
  so.realtime = cam.realtime;
  so.settings = cam.settings;
  return openCameraSource(cam.source, so, &report);
}

OutputOptions outputOptionsFor(const SiteConfig& c, bool publish_geometry) {
  OutputOptions o;
  o.group = c.network.vision_group;
  o.port = c.network.vision_port;
  o.interface_addr = c.network.interface_addr;
  o.publish_geometry = publish_geometry;
  o.ssl_log = c.record.ssl_log;
  o.who = "dotvision serve";
  return o;
}
}  // namespace

SiteRuntime::SiteRuntime(const SiteConfig& config, LogFn log) : config_(config), log_(std::move(log)) {
  rebuildHeights();
  // Sources first: a synthetic camera brings its scene's geometry.
  std::vector<std::unique_ptr<CameraSource>> sources(config_.cameras.size());
  std::vector<const Geometry*> scene_geometry(config_.cameras.size(), nullptr);
  for (size_t i = 0; i < config_.cameras.size(); ++i) {
    const SiteCamera& cam = config_.cameras[i];
    try {
      std::vector<std::string> report;
      sources[i] = openSiteSource(cam, report);
      for (const std::string& line : report) log_(cameraName(cam) + ": " + line);
      if (auto* synthetic = dynamic_cast<SyntheticCamera*>(sources[i].get())) scene_geometry[i] = &synthetic->geometry();
    } catch (const std::exception& e) {
      log_(cameraName(cam) + " (" + config_.path + ":" + std::to_string(cam.line) + "): not started: " + e.what());
    }
  }
  const SiteNetwork& net = config_.network;
  bool publish_geometry = true;
  if (net.geometry == "file" || net.geometry == "publish") {
    geometry_ = loadGeometry(net.geometry_file);
    publish_geometry = net.geometry == "file";
  } else if (net.geometry == "publisher" ||
             std::none_of(scene_geometry.begin(), scene_geometry.end(), [](const Geometry* g) { return g; })) {
    // Wait for the geometry publisher: the field and each camera's calibration.
    publish_geometry = false;
    GeometryReceiveOptions ro;
    ro.group = net.vision_group;
    ro.port = net.vision_port;
    ro.interface_addr = net.interface_addr;
    for (const SiteCamera& cam : config_.cameras) {
      auto g = receiveGeometry(cam.id, net.geometry_timeout, ro);
      if (!g) {
        log_(cameraName(cam) + ": no calibration from the geometry publisher within " +
             std::to_string(net.geometry_timeout) + " s");
        continue;
      }
      geometry_.field = g->field;
      if (const CameraCalibration* c = g->camera(cam.id)) geometry_.cameras.push_back(*c);
    }
  } else {  // auto with synthetic cameras: their scenes' field and calibrations
    for (size_t i = 0; i < scene_geometry.size(); ++i) {
      if (!scene_geometry[i]) continue;
      geometry_.field = scene_geometry[i]->field;
      if (const CameraCalibration* c = scene_geometry[i]->camera(config_.cameras[i].id))
        geometry_.cameras.push_back(*c);
    }
  }
  // What the cameras use is what is published (and written to a raw dump):
  // the protocol's single-precision floats, so replays match to the bit.
  geometry_ = withWirePrecision(geometry_, "geometry");
  if (net.geometry == "publish") {
    GeometryPublisherOptions po;
    po.group = net.vision_group;
    po.port = net.vision_port;
    po.interface_addr = net.interface_addr;
    geometry_publisher_ = std::make_unique<GeometryPublisher>(geometry_, po);
  }
  outputs_ = std::make_unique<PacketOutputs>(outputOptionsFor(config_, publish_geometry), toProto(geometry_));

  for (size_t i = 0; i < config_.cameras.size(); ++i) {
    if (!sources[i]) continue;
    const SiteCamera& cam = config_.cameras[i];
    const CameraCalibration* calib = geometry_.camera(cam.id);
    if (!calib) {
      log_(cameraName(cam) + ": not started: the geometry has no calibration for it");
      continue;
    }
    runners_.push_back(std::make_unique<CameraRunner>(*calib, geometry_.field, processorOptions(cam),
                                                      std::move(sources[i]), *outputs_, log_));
    config_index_.push_back(i);
    if (!config_.record.raw_dir.empty()) {
      auto ring = std::make_shared<RawRing>(config_.record.raw_seconds, kRawRingBytes);
      runners_.back()->addFrameHook([ring, buffer = std::string()](const Frame& f, const ssl::SSL_WrapperPacket& p) mutable {
        p.SerializeToString(&buffer);  // reuses the buffer's capacity
        ring->add(f, buffer);
      });
      rings_.push_back(ring);
    }
  }
  if (!rings_.empty())
    log_("keeping the last " + std::to_string(config_.record.raw_seconds) + " s of raw frames per camera for " +
         config_.record.raw_dir + " (SIGUSR1" + (config_.record.on_health_change ? " or a change of health" : "") +
         " writes them)");
  if (runners_.empty()) throw InputError(config_.path, "no camera could be started (see the lines above)");
}

SiteRuntime::~SiteRuntime() { stop(); }

DetectorOptions SiteRuntime::detectorOptions() const {
  DetectorOptions d;
  d.report_guessed_ids = config_.detector.guessed_ids;
  d.tracking = config_.detector.tracking;
  d.ball_radius = config_.detector.ball_radius;
  d.robot_height_yellow = current_heights_.yellow_mm;
  d.robot_height_blue = current_heights_.blue_mm;
  return d;
}

void SiteRuntime::rebuildHeights() {
  const SiteRobotHeights& h = config_.robot_heights;
  TeamHeights next(h.default_mm, config_.path);
  for (const auto& [name, mm] : h.teams) next.addTeam(name, mm, config_.path);
  if (h.yellow_mm) next.setYellow(*h.yellow_mm, config_.path);
  if (h.blue_mm) next.setBlue(*h.blue_mm, config_.path);
  heights_ = std::move(next);
  current_heights_ = heights_.resolve(referee_);
  for (const std::string& w : current_heights_.warnings) log_(w);
}

ProcessorOptions SiteRuntime::processorOptions(const SiteCamera& cam) const {
  ProcessorOptions o;
  // Each camera's pipeline gets an even share of the cores unless told.
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.pipeline.threads = cam.threads > 0 ? cam.threads
                                       : std::max(1, cores / static_cast<int>(std::max<size_t>(1, config_.cameras.size())));
  if (!parseBackend(cam.backend.c_str(), o.backend.backend))
    throw InputError(config_.path + ":" + std::to_string(cam.line), "unknown backend '" + cam.backend + "'");
  o.pipeline.bayer_sampling = bayerSamplingFromName(cam.bayer_sampling);
  o.pipeline.coarse_search = !cam.full_search;
  o.detector = detectorOptions();
  return o;
}

void SiteRuntime::start() {
  if (geometry_publisher_) {
    geometry_publisher_->start();
    geometry_thread_ = std::thread([this] {
      while (geometry_publisher_->step(0.1)) {
      }
    });
  }
  for (auto& r : runners_) r->start();
}

bool SiteRuntime::dumpRaw(const std::string& why) {
  if (rings_.empty() || dumping_.exchange(true)) return false;
  if (dump_thread_.joinable()) dump_thread_.join();
  std::vector<RawDumpCamera> cams;
  size_t frames = 0;
  for (size_t i = 0; i < rings_.size(); ++i) {
    cams.push_back({runners_[i]->cameraId(), rings_[i]->snapshot()});
    frames += cams.back().frames.size();
  }
  if (frames == 0) {
    log_("raw frames not written (" + why + "): no frame processed yet");
    dumping_ = false;
    return true;
  }
  const std::time_t t = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&t));
  const std::string dir = config_.record.raw_dir + "/" + stamp;
  dump_thread_ = std::thread([this, cams = std::move(cams), dir, why, geometry = geometry_] {
    try {
      const size_t n = writeRawDump(dir, cams, geometry);
      log_("raw frames written (" + why + "): " + std::to_string(n) + " frames in " + dir +
           "; replay with: dotvision run --source " + dir + " --geometry " + dir + "/geometry.json --camera-id " +
           std::to_string(cams.front().camera_id));
    } catch (const std::exception& e) {
      log_(std::string("raw frames not written: ") + e.what());
    }
    dumping_ = false;
  });
  return true;
}

void SiteRuntime::stop() {
  for (auto& r : runners_) r->stop();
  if (geometry_publisher_) geometry_publisher_->stop();
  if (geometry_thread_.joinable()) geometry_thread_.join();
  if (dump_thread_.joinable()) dump_thread_.join();
}

std::vector<CameraStatus> SiteRuntime::status() {
  std::vector<CameraStatus> out;
  out.reserve(runners_.size());
  std::string changed;
  for (auto& r : runners_) {
    out.push_back(r->status());
    if (out.back().health_changed) changed += (changed.empty() ? "camera " : ", ") + std::to_string(out.back().camera_id);
  }
  if (!changed.empty() && config_.record.on_health_change) dumpRaw("health changed on " + changed);
  return out;
}

void SiteRuntime::setReferee(const RefereeSnapshot& referee) {
  referee_ = referee;
  current_heights_ = heights_.resolve(referee_);
  for (const std::string& w : current_heights_.warnings) log_(w);
  const DetectorOptions d = detectorOptions();
  for (auto& r : runners_) r->setDetectorOptions(d);
}

void SiteRuntime::tick() {
  outputs_->tick();
  std::lock_guard<std::mutex> lock(sent_mutex_);
  if (sent_.cameras.empty() || std::chrono::steady_clock::now() < sent_.next) return;
  sent_.next = std::chrono::steady_clock::now() + kCalibrationResendInterval;
  try {
    CalibrationSender(sent_.addr, sent_.port).send(geometry_.field, sent_.cameras);
  } catch (const InputError&) {  // the address was good when it was first sent to
  }
}

std::vector<std::string> SiteRuntime::setCalibration(const CameraCalibration& c, const std::string& publisher) {
  const std::string name = "camera " + std::to_string(c.camera_id);
  auto runner = std::find_if(runners_.begin(), runners_.end(), [&](const auto& r) { return r->cameraId() == c.camera_id; });
  if (runner == runners_.end()) throw InputError(name, "no camera of this id runs here");
  std::vector<std::string> notes = useCalibration(**runner, geometry_, *outputs_, c);
  // To a geometry publisher, in this process or outside, the wire way.
  std::string addr = "127.0.0.1";
  uint16_t port = kGeometryListenPort;
  if (geometry_publisher_) {
    port = geometry_publisher_->listenPort();
  } else if (config_.network.geometry == "publisher" || !outputs_->publishesGeometry()) {
    if (!publisher.empty() && !splitListenAddress(publisher, addr, port)) {
      addr = publisher;
      port = kGeometryListenPort;
    }
  } else {
    return notes;
  }
  {
    std::lock_guard<std::mutex> lock(sent_mutex_);
    if (sent_.addr != addr || sent_.port != port) sent_.cameras.clear();
    sent_.addr = addr;
    sent_.port = port;
    std::erase_if(sent_.cameras, [&](const CameraCalibration& s) { return s.camera_id == c.camera_id; });
    sent_.cameras.push_back(c);
    sent_.next = std::chrono::steady_clock::now() + kCalibrationResendInterval;
  }
  CalibrationSender sender(addr, port);
  if (sender.send(geometry_.field, {c}))
    notes.push_back("sent to the geometry publisher at " + addr + ":" + std::to_string(port));
  else
    notes.push_back("could not send it to the geometry publisher at " + addr + ":" + std::to_string(port));
  return notes;
}

// The geometry file is read again on each reload: a camera whose
// calibration changed (another lens, a camera of another size) gets it as a
// console-accepted one does; frames that no longer fit it are then skipped
// and counted. A file that does not load keeps what runs.
void SiteRuntime::reloadGeometry(const SiteConfig& next, std::vector<std::string>& notes) {
  const std::string& mode = config_.network.geometry;
  if (mode != "file" && mode != "publish") return;
  if (next.network.geometry != mode || next.network.geometry_file != config_.network.geometry_file) {
    notes.push_back("geometry source or file changed: restart serve to use it");
    return;
  }
  const std::string& file = config_.network.geometry_file;
  Geometry g;
  try {
    g = geometryFromProto(toProto(loadGeometry(file)), file);
  } catch (const std::exception& e) {
    notes.push_back(std::string("geometry not reloaded, the running one stays: ") + e.what());
    return;
  }
  if (toProto(g.field).SerializeAsString() != toProto(geometry_.field).SerializeAsString())
    notes.push_back(file + ": the field changed: restart serve to use it");
  for (auto& r : runners_) {
    const uint32_t id = r->cameraId();
    const CameraCalibration* now = geometry_.camera(id);
    const CameraCalibration* c = g.camera(id);
    const std::string name = "camera " + std::to_string(id);
    if (!c) {
      notes.push_back(name + ": not in " + file + "; it keeps its calibration");
    } else if (!now || !(*c == *now)) {
      notes.push_back(name + ": new calibration from " + file + " (" + std::to_string(c->image_width) + " x " +
                      std::to_string(c->image_height) + " px)");
      for (std::string& n : setCalibration(*c, "")) notes.push_back(std::move(n));
    }
  }
}

std::vector<std::string> SiteRuntime::reload(const SiteConfig& next) {
  std::vector<std::string> notes;
  // Cameras are matched by id; a changed source or a new or removed camera needs a restart.
  for (const SiteCamera& n : next.cameras) {
    auto old = std::find_if(config_.cameras.begin(), config_.cameras.end(), [&](const SiteCamera& c) { return c.id == n.id; });
    if (old == config_.cameras.end()) notes.push_back("camera " + std::to_string(n.id) + " is new: restart serve to start it");
    else if (old->source != n.source) notes.push_back("camera " + std::to_string(n.id) + " has a new source: restart serve to use it");
  }
  for (const SiteCamera& c : config_.cameras)
    if (std::none_of(next.cameras.begin(), next.cameras.end(), [&](const SiteCamera& n) { return n.id == c.id; }))
      notes.push_back("camera " + std::to_string(c.id) + " is no longer listed: restart serve to stop it");

  const SiteConfig previous = config_;
  config_.robot_heights = next.robot_heights;
  config_.detector = next.detector;
  rebuildHeights();
  config_.status_interval = next.status_interval;
  const DetectorOptions d = detectorOptions();
  for (size_t i = 0; i < runners_.size(); ++i) {
    runners_[i]->setDetectorOptions(d);
    SiteCamera& cur = config_.cameras[config_index_[i]];
    auto n = std::find_if(next.cameras.begin(), next.cameras.end(), [&](const SiteCamera& c) { return c.id == cur.id; });
    if (n == next.cameras.end() || n->source != cur.source) continue;
    bool same = n->settings.size() == cur.settings.size();
    for (size_t k = 0; same && k < cur.settings.size(); ++k)
      same = n->settings[k].name == cur.settings[k].name && n->settings[k].value == cur.settings[k].value;
    if (same) continue;
    try {
      for (const std::string& line : runners_[i]->source().applySettings(n->settings))
        notes.push_back("camera " + std::to_string(cur.id) + ": " + line);
      cur.settings = n->settings;
    } catch (const std::exception& e) {
      notes.push_back("camera " + std::to_string(cur.id) + ": settings not applied: " + e.what());
    }
  }
  if (next.network.vision_group != previous.network.vision_group ||
      next.network.vision_port != previous.network.vision_port ||
      next.network.interface_addr != previous.network.interface_addr) {
    config_.network.vision_group = next.network.vision_group;
    config_.network.vision_port = next.network.vision_port;
    config_.network.interface_addr = next.network.interface_addr;
    try {
      outputs_->retarget(outputOptionsFor(config_, outputs_->publishesGeometry()));
      notes.push_back("publishing to " + config_.network.vision_group + ":" + std::to_string(config_.network.vision_port));
    } catch (const std::exception& e) {
      notes.push_back(std::string("network target not changed: ") + e.what());
    }
  }
  reloadGeometry(next, notes);
  char heights[96];
  std::snprintf(heights, sizeof heights, "yellow %.1f mm, blue %.1f mm", current_heights_.yellow_mm,
                current_heights_.blue_mm);
  notes.push_back(std::string("detector options and robot heights applied (") + heights + ")");
  return notes;
}

}  // namespace dv::app

// `dotvision run`: frames from a source (images, video, or the built-in
// synthetic scene) -> pixel pipeline -> detector -> SSL_DetectionFrame,
// multicast on the league's vision port and optionally recorded (SSL log,
// JSONL). Ends at the end of the source with a short summary; on the
// synthetic scene it also compares with the scene's truth.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/camera_processor.h"

#include "app/camera_runner.h"
#include "app/commands.h"
#include "app/packet_outputs.h"
#include "app/run_console.h"
#include "app/run_progress.h"
#include "app/signals.h"
#include "camera/open_camera.h"
#include "app/debug_views.h"
#include "app/synthetic_camera.h"
#include "app/synthetic_source.h"
#include "core/clock.h"
#include "core/error.h"
#include "dotvision/ssl_wrapper.pb.h"
#include "eval/metrics.h"
#include "geometry/geometry_io.h"
#include "net/geometry_publisher.h"
#include "geometry/proto_json.h"
#include "detection/color_health.h"
#include "detection/detection_frame.h"
#include "io/frame_source.h"
#include "io/ssl_log.h"
#include "net/vision_publisher.h"
#include "pipeline/bayer_layout_check.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv::app {

namespace {

using Clock = std::chrono::steady_clock;

struct RunArgs {
  std::string source;
  std::string geometry;
  std::optional<uint32_t> camera_id;
  std::string scene;
  std::string bayer = "rggb";
  std::string bayer_sampling = "auto";
  bool full_search = false;
  double fps = 60;
  std::string record;
  std::string jsonl;
  bool no_publish = false;
  bool no_guessed_ids = false;
  std::string multicast_group = "224.5.23.2";
  uint16_t multicast_port = 10006;
  std::string multicast_interface;
  std::string debug_dir;
  long debug_frame = 0;
  int threads = 0;
  std::string backend = "auto";
  std::string opencl_platform;
  std::string opencl_device;
  long max_frames = -1;
  double geometry_timeout = 10;
  bool quiet = false;
  bool realtime = false;
  std::vector<std::string> camera_set;
  std::optional<double> robot_height, robot_height_yellow, robot_height_blue;
  double status_interval = 5;
  std::string http;  // --http: the console
  bool http_given = false;
};

OutputOptions outputOptions(const RunArgs& a, bool publish_geometry) {
  OutputOptions o;
  o.publish = !a.no_publish;
  o.group = a.multicast_group;
  o.port = a.multicast_port;
  o.interface_addr = a.multicast_interface;
  o.publish_geometry = publish_geometry;
  o.ssl_log = a.record;
  o.jsonl = a.jsonl;
  return o;
}


// One camera: its processor (built on the first frame, whose size and pixel
// format it then expects), reused detections and packet, and statistics.
struct Channel {
  CameraCalibration calibration;
  std::optional<CameraProcessor> processor;
  Detections detections;
  ssl::SSL_WrapperPacket packet;
  long processed = 0;
  long robots = 0;
  long balls = 0;
  std::vector<double> pipeline_ms, detection_ms, total_ms;
  ColorHealthWatch colors;  // color classes missing or collapsing (color_health.h)
};

struct RunState {
  const RunArgs& args;
  FieldModel field;
  ProcessorOptions options;
  PacketOutputs& outputs;
  std::vector<SkipRecord> skipped;
  Metrics truth_metrics;
  bool have_truth = false;
  std::vector<std::string> debug_written;
};

ProcessorOptions processorOptions(const RunArgs& a) {
  ProcessorOptions o;
  o.pipeline.threads = a.threads;
  if (!parseBackend(a.backend.c_str(), o.backend.backend))
    throw InputError("command line", "unknown --backend '" + a.backend + "' (expected cpu, opencl or auto)");
  o.backend.opencl_platform = a.opencl_platform;
  o.backend.opencl_device = a.opencl_device;
  o.pipeline.bayer_sampling = bayerSamplingFromName(a.bayer_sampling);
  o.pipeline.coarse_search = !a.full_search;
  o.detector.report_guessed_ids = !a.no_guessed_ids;
  if (a.robot_height) o.detector.robot_height_yellow = o.detector.robot_height_blue = *a.robot_height;
  if (a.robot_height_yellow) o.detector.robot_height_yellow = *a.robot_height_yellow;
  if (a.robot_height_blue) o.detector.robot_height_blue = *a.robot_height_blue;
  return o;
}

void reportSkip(RunState& s, const std::string& name, const std::string& reason) {
  std::fprintf(stderr, "dotvision run: skipped %s: %s\n", name.c_str(), reason.c_str());
  s.skipped.push_back({name, reason});
}

// Processes one frame of one camera; false if the frame was skipped.
bool processFrame(RunState& s, Channel& ch, const Frame& frame) {
  if (!ch.processor) {
    CameraCalibration c = ch.calibration;
    if (c.image_width == 0 || c.image_height == 0) {  // geometry without image size: take the frame's
      c.image_width = static_cast<uint32_t>(frame.image.cols);
      c.image_height = static_cast<uint32_t>(frame.image.rows);
    }
    ProcessorOptions o = s.options;
    o.pipeline.bayer = bayerPatternOf(frame.format);
    ch.processor.emplace(c, s.field, o);
    std::printf("dotvision run: camera %u: %s\n", ch.calibration.camera_id,
                ch.processor->pipeline().samplingNote().c_str());
    std::fflush(stdout);
    const std::string layout = bayerLayoutWarning(frame.image, o.pipeline.bayer);
    if (!layout.empty())
      std::fprintf(stderr, "dotvision run: warning: camera %u, %s: %s\n", ch.calibration.camera_id,
                   frame.name.c_str(), layout.c_str());
    const size_t expect = static_cast<size_t>(s.args.max_frames > 0 ? s.args.max_frames : 4096);
    ch.pipeline_ms.reserve(expect);
    ch.detection_ms.reserve(expect);
    ch.total_ms.reserve(expect);
  }
  std::string why;
  if (!ch.processor->process(frame, ch.detections, why)) {
    reportSkip(s, frame.name, why);
    return false;
  }
  FrameStamp stamp;
  stamp.camera_id = ch.calibration.camera_id;
  stamp.frame_number = frame.index;
  stamp.t_capture = frame.t_capture;
  stamp.t_sent = unixSeconds();
  fillDetectionPacket(ch.detections, stamp, ch.packet);
  s.outputs.detection(ch.packet);

  const unsigned color_changes = ch.colors.update(ch.processor->detector().health());
  if (color_changes || ch.colors.castChanged())
    ch.colors.sayChanges(color_changes, [&](bool warning, const std::string& text) {
      std::fprintf(warning ? stderr : stdout, "dotvision run: %scamera %u: %s\n", warning ? "warning: " : "",
                   ch.calibration.camera_id, text.c_str());
    });
  ++ch.processed;
  ch.robots += static_cast<long>(ch.detections.robots.size());
  ch.balls += static_cast<long>(ch.detections.balls.size());
  ch.pipeline_ms.push_back(ch.processor->lastPipelineMs());
  ch.detection_ms.push_back(ch.processor->lastDetectionMs());
  ch.total_ms.push_back(ch.processor->lastPipelineMs() + ch.processor->lastDetectionMs());

  if (!s.args.debug_dir.empty() && static_cast<long>(frame.index) == s.args.debug_frame) {
    auto written = writeDebugViews(s.args.debug_dir, stamp.camera_id, frame, *ch.processor, ch.detections);
    s.debug_written.insert(s.debug_written.end(), written.begin(), written.end());
  }
  return true;
}

void printSummary(const RunState& s, const std::string& what, const std::vector<Channel>& channels) {
  long processed = 0, robots = 0, balls = 0;
  std::vector<double> pipe, det, total;
  for (const Channel& c : channels) {
    processed += c.processed;
    robots += c.robots;
    balls += c.balls;
    pipe.insert(pipe.end(), c.pipeline_ms.begin(), c.pipeline_ms.end());
    det.insert(det.end(), c.detection_ms.begin(), c.detection_ms.end());
    total.insert(total.end(), c.total_ms.begin(), c.total_ms.end());
  }
  const double per = processed > 0 ? 1.0 / processed : 0;
  std::printf("dotvision run: %s\n", what.c_str());
  std::printf("  frames: %ld processed, %zu skipped\n", processed, s.skipped.size());
  for (const Channel& c : channels)
    if (c.processor)
      std::printf("  camera %u: backend %s\n", c.calibration.camera_id, c.processor->pipeline().name().c_str());
  std::printf("  detections: %ld robots (%.2f per frame), %ld balls (%.2f per frame)\n", robots,
              robots * per, balls, balls * per);
  if (processed > 0 && robots == 0 && balls == 0)
    std::printf("  nothing was detected: check --bayer, the geometry and --camera-id\n");
  for (const Channel& c : channels) {
    const std::string colors = c.colors.summary();
    if (!colors.empty()) std::printf("  colors, camera %u: %s\n", c.calibration.camera_id, colors.c_str());
  }
  if (!total.empty()) {
    std::printf("  time per frame: pipeline median %.2f ms, detection median %.2f ms, "
                "total median %.2f ms, p99 %.2f ms\n",
                percentile(pipe, 0.5), percentile(det, 0.5), percentile(total, 0.5),
                percentile(total, 0.99));
  }
  if (s.have_truth) {
    const Metrics& m = s.truth_metrics;
    const ErrorStats pos = errorStats(m.robot_position_errors_mm);
    const ErrorStats ori = errorStats(m.robot_orientation_errors_rad);
    const ErrorStats bpos = errorStats(m.ball_position_errors_mm);
    std::printf("  vs truth: robots recall %.3f, precision %.3f (team recall %.3f, id accuracy %.3f), "
                "position error median %.1f mm / p95 %.1f mm, orientation error median %.3f rad\n",
                m.robotRecall(), m.robotPrecision(), m.teamRecall(), m.idAccuracy(), pos.median,
                pos.p95, ori.median);
    std::printf("            balls recall %.3f, precision %.3f, position error median %.1f mm; "
                "false positives %.2f per frame\n",
                m.ballRecall(), m.ballPrecision(), bpos.median, m.falsePositivesPerFrame());
  }
  std::printf("  output: %s\n", s.outputs.describe().c_str());
  if (!s.debug_written.empty())
    std::printf("  debug views: %zu images in %s\n", s.debug_written.size(), s.args.debug_dir.c_str());
  if (!s.skipped.empty()) {
    std::printf("  skipped frames:\n");
    const size_t show = std::min<size_t>(s.skipped.size(), 20);
    for (size_t i = 0; i < show; ++i)
      std::printf("    %s: %s\n", s.skipped[i].name.c_str(), s.skipped[i].reason.c_str());
    if (show < s.skipped.size()) std::printf("    ... and %zu more\n", s.skipped.size() - show);
  }
}

std::string cameraIds(const Geometry& g) {
  std::string out;
  for (const auto& c : g.cameras) out += (out.empty() ? "" : ", ") + std::to_string(c.camera_id);
  return out.empty() ? "none" : out;
}

std::string formatSeconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f s", s);
  return buf;
}

// The geometry of a run on a real source: from --geometry, or else from the
// geometry publisher on the vision group (the field and this camera's
// calibration), waiting at most --geometry-timeout seconds.
Geometry sourceGeometry(const RunArgs& a, bool& from_network) {
  from_network = a.geometry.empty();
  if (!from_network) return loadGeometry(a.geometry);
  if (!a.camera_id)
    throw InputError("command line", "--source without --geometry needs --camera-id (to take that "
                                     "camera's calibration from the geometry publisher)");
  GeometryReceiveOptions ro;
  ro.group = a.multicast_group;
  ro.port = a.multicast_port;
  ro.interface_addr = a.multicast_interface;
  auto g = receiveGeometry(*a.camera_id, a.geometry_timeout, ro);
  if (!g)
    throw InputError("udp " + a.multicast_group + ":" + std::to_string(a.multicast_port),
                     "no geometry with a calibration for camera " + std::to_string(*a.camera_id) +
                         " within " + formatSeconds(a.geometry_timeout) +
                         " (run `dotvision geometry`, or pass --geometry)");
  return *g;
}

// A camera, or files paced with --realtime: capture and processing threads
// with the latest frame winning, a status line every few seconds, and a
// summary with the latency from a frame's arrival to its packet.
int runLive(const RunArgs& a, const CameraCalibration& calibration, const Geometry& geometry,
            std::unique_ptr<CameraSource> source, PacketOutputs& outputs) {
  const FieldModel& field = geometry.field;
  const std::string name = source->describe();
  auto log = [](const std::string& line) {
    std::fprintf(stderr, "dotvision run: %s\n", line.c_str());
  };
  CameraRunner runner(calibration, field, processorOptions(a), std::move(source), outputs, log);
  // The console of serve over this one camera; it hooks in before the start.
  std::unique_ptr<RunConsole> console;
  if (a.http_given) console = std::make_unique<RunConsole>(runner, geometry, outputs, a.http, log);
  const auto started = Clock::now();
  runner.start();
  if (console) console->start();
  auto next_line = started + std::chrono::duration<double>(a.status_interval);
  auto next_second = started + std::chrono::seconds(1);
  CameraStatus last;
  while (!stopRequested() && !runner.ended()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(console ? 20 : 50));
    outputs.tick();
    if (console) console->service();
    const auto now = Clock::now();
    // Once a second (the console's rates and health), the line at the interval.
    if (console ? now >= next_second : now >= next_line) {
      next_second = now + std::chrono::seconds(1);
      last = runner.status();
      if (console) console->setStatus(last);
    }
    if (now >= next_line) {
      if (!a.quiet && a.status_interval > 0) std::fprintf(stderr, "%s", statusLine(last).c_str());
      next_line += std::chrono::duration<double>(a.status_interval);
    }
    if (a.max_frames >= 0 && runner.processed() >= static_cast<uint64_t>(a.max_frames)) break;
  }
  console.reset();
  runner.stop();
  outputs.finish();
  last = runner.status();
  const LiveCounters& c = last.counters;
  const CameraRunner::Times t = runner.times();
  const double secs = std::chrono::duration<double>(Clock::now() - started).count();
  std::printf("dotvision run: %s, camera %u%s\n", name.c_str(), calibration.camera_id,
              stopRequested() ? " (stopped by a signal)" : "");
  std::printf("  frames: %llu received, %llu processed, %llu dropped (latest frame wins), %llu skipped, "
              "%llu lost while the camera was away; %.1f s\n",
              static_cast<unsigned long long>(c.frames_in), static_cast<unsigned long long>(c.processed),
              static_cast<unsigned long long>(c.dropped), static_cast<unsigned long long>(c.skipped),
              static_cast<unsigned long long>(c.gap_frames), secs);
  if (c.losses) std::printf("  camera lost %llu times, back %llu times\n", static_cast<unsigned long long>(c.losses),
                            static_cast<unsigned long long>(c.reconnects));
  if (!t.total_ms.empty())
    std::printf("  latency arrival -> sent: p50 %.2f ms, p99 %.2f ms; pipeline median %.2f ms, detection median %.2f ms\n",
                percentile(t.total_ms, 0.5), percentile(t.total_ms, 0.99), percentile(t.pipeline_ms, 0.5),
                percentile(t.detection_ms, 0.5));
  std::printf("  output: %s\n", outputs.describe().c_str());
  if (!runner.failure().empty()) return kExitBadInput;
  return c.processed > 0 && outputs.recordingFailure().empty() ? kExitOk : kExitFailure;
}

int runOnSource(const RunArgs& a) {
  bool from_network = false;
  // synthetic://SCENE/ID: a camera of a synthetic scene, live, with the
  // scene's geometry unless --geometry says otherwise.
  std::unique_ptr<SyntheticCamera> synthetic;
  if (isSyntheticSpec(a.source)) synthetic = std::make_unique<SyntheticCamera>(a.source);
  const Geometry geometry = synthetic && a.geometry.empty() ? synthetic->geometry() : sourceGeometry(a, from_network);
  const std::string geometry_source =
      from_network ? std::string("network geometry") : a.geometry.empty() ? a.source : a.geometry;
  const CameraCalibration* calibration = nullptr;
  if (a.camera_id || synthetic) {
    calibration = geometry.camera(a.camera_id ? *a.camera_id : synthetic->cameraId());
    if (!calibration)
      throw InputError(geometry_source, "no calibration for camera id " +
                                            std::to_string(a.camera_id ? *a.camera_id : synthetic->cameraId()) +
                                            " (calibrations present: " + cameraIds(geometry) + ")");
  } else if (geometry.cameras.size() == 1) {
    calibration = &geometry.cameras.front();
  } else {
    throw InputError("command line", "--camera-id is needed: " + geometry_source +
                                         " has calibrations for cameras " + cameraIds(geometry));
  }
  CameraSourceOptions so;
  so.files.fps = a.fps;
  so.files.bayer = bayerFormatFromName(a.bayer, "--bayer");
  so.files.scene_camera = calibration->camera_id;
  so.files.time_origin = unixSeconds();  // packets carry Unix time, spaced as the files are
  so.realtime = a.realtime;
  for (const std::string& item : a.camera_set) so.settings.push_back(parseCameraSetting(item, "--camera-set"));
  std::vector<std::string> settings_report;
  std::unique_ptr<CameraSource> source =
      synthetic ? std::move(synthetic) : openCameraSource(a.source, so, &settings_report);
  for (const std::string& line : settings_report)
    std::printf("dotvision run: %s: %s\n", a.source.c_str(), line.c_str());

  PacketOutputs outputs(outputOptions(a, !from_network), toProto(geometry));
  if (source->live()) return runLive(a, *calibration, geometry, std::move(source), outputs);
  if (a.http_given)
    throw InputError("--http", "the console needs a live source: a camera, synthetic://SCENE/ID, or files with --realtime");

  RunState state{a, geometry.field, processorOptions(a), outputs, {}, {}, false, {}};
  std::vector<Channel> channels(1);
  channels[0].calibration = *calibration;

  Frame frame;
  std::string why;
  long frames = 0;
  RunProgress progress(source->expectedCount(), !a.quiet);
  while ((a.max_frames < 0 || frames < a.max_frames) && !stopRequested()) {
    const GrabStatus st = source->grab(frame, 1.0, why);
    if (st == GrabStatus::End) break;
    if (st == GrabStatus::Skipped) {
      const size_t colon = why.find(": ");
      reportSkip(state, why.substr(0, colon), colon == std::string::npos ? why : why.substr(colon + 2));
      progress.update(frames + static_cast<long>(state.skipped.size()));
      continue;
    }
    if (st != GrabStatus::Frame) continue;
    ++frames;
    processFrame(state, channels[0], frame);
    progress.update(frames + static_cast<long>(state.skipped.size()));
  }
  progress.finish();
  outputs.finish();
  printSummary(state, source->describe() + ", camera " + std::to_string(calibration->camera_id) +
                          (stopRequested() ? " (stopped by a signal)" : ""),
               channels);
  if (channels[0].processed == 0) {
    std::fprintf(stderr, "dotvision run: %s: no frame could be processed\n", a.source.c_str());
    return kExitBadInput;
  }
  return outputs.recordingFailure().empty() ? kExitOk : kExitFailure;
}

int runSynthetic(const RunArgs& a) {
  SceneSpec spec = a.scene.empty() ? defaultScene()
                   : (a.scene.find('/') != std::string::npos || a.scene.find('.') != std::string::npos)
                       ? loadScene(a.scene)
                       : presetScene(a.scene);
  if (a.max_frames >= 0) spec.frames = static_cast<int>(std::min<long>(spec.frames, a.max_frames));

  std::vector<size_t> camera_indices;
  std::string ids;
  for (size_t i = 0; i < spec.cameras.size(); ++i) {
    ids += (ids.empty() ? "" : ", ") + std::to_string(spec.cameras[i].calib.camera_id);
    if (!a.camera_id || spec.cameras[i].calib.camera_id == *a.camera_id) camera_indices.push_back(i);
  }
  if (camera_indices.empty())
    throw InputError("scene '" + spec.name + "'",
                     "has no camera with id " + std::to_string(*a.camera_id) + " (cameras: " + ids + ")");
  SyntheticSource source(spec, camera_indices);
  const Geometry geometry = source.renderer().geometry();

  PacketOutputs outputs(outputOptions(a, true), toProto(geometry));
  const double origin = unixSeconds();  // packets carry Unix time
  RunState state{a, geometry.field, processorOptions(a), outputs, {}, {}, true, {}};
  // Channel k serves scene camera camera_indices[k].
  std::vector<Channel> channels(camera_indices.size());
  std::vector<size_t> channel_of(spec.cameras.size(), 0);
  for (size_t k = 0; k < camera_indices.size(); ++k) {
    channels[k].calibration = spec.cameras[camera_indices[k]].calib;
    channel_of[camera_indices[k]] = k;
  }

  const MatchOptions match;
  Frame frame;
  while (!stopRequested() && source.next(frame)) {
    frame.t_capture += origin;
    Channel& ch = channels[channel_of[source.cameraIndex()]];
    const bool ok = processFrame(state, ch, frame);
    scoreFrame(source.truth(), ok ? &ch.packet.detection() : nullptr, match, state.truth_metrics);
  }
  outputs.finish();
  std::string cams;
  for (const Channel& c : channels) cams += (cams.empty() ? "" : ", ") + std::to_string(c.calibration.camera_id);
  const CameraCalibration& first = channels.front().calibration;
  printSummary(state,
               source.describe() + ", camera " + cams + ", " + std::to_string(first.image_width) + "x" +
                   std::to_string(first.image_height) + (spec.bayer ? " Bayer" : " RGB") +
                   (stopRequested() ? " (stopped by a signal)" : ""),
               channels);
  return outputs.recordingFailure().empty() ? kExitOk : kExitFailure;
}

}  // namespace

CommandFn addRunCommand(CLI::App& root) {
  auto a = std::make_shared<RunArgs>();
  CLI::App* cmd = root.add_subcommand(
      "run",
      "Detect robots and balls in a camera's frames and publish them as SSL_DetectionFrame. "
      "Without --source it runs on the built-in synthetic scene and compares with its truth.");
  cmd->add_option("--source", a->source,
                  "genicam://ID (Aravis id or serial; genicam:// for the only camera), v4l2:///dev/videoN, "
                  "synthetic://SCENE/ID (a camera of a synthetic scene, live; its geometry unless --geometry), "
                  "rtsp://..., http://... (MJPEG), image file, directory of images (sorted by name; in a `dotvision synth` directory only "
                  "the chosen camera's frames), quoted glob ('dir/*.png') or video file. Color images are "
                  "RGB; 8-bit single-channel images are Bayer mosaics");
  cmd->add_option("--geometry", a->geometry,
                  "SSL_GeometryData as canonical JSON (or YAML); without it, a --source run takes the "
                  "field and its calibration from the geometry publisher on the vision group");
  cmd->add_option("--geometry-timeout", a->geometry_timeout,
                  "seconds to wait for network geometry (default 10)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--camera-id", a->camera_id, "camera id whose calibration is used");
  cmd->add_option("--scene", a->scene,
                  "without --source: a scene YAML file or preset name instead of the built-in scene");
  cmd->add_option("--bayer", a->bayer, "Bayer layout of single-channel images: rggb|grbg|gbrg|bggr")
      ->default_str("rggb");
  cmd->add_option("--bayer-sampling", a->bayer_sampling,
                  "Bayer mosaic sampling: auto|subsample|full (auto: a sample per pixel where 2x2 cells "
                  "are coarse on the field, else one per 2x2 cell)")
      ->default_str("auto");
  cmd->add_flag("--full-search", a->full_search,
                "find blobs on the full grid everywhere (CPU; default: a coarse search on a grid of twice the "
                "spacing where the grid is fine, then the full grid only around its peaks)");
  cmd->add_option("--fps", a->fps, "frame rate for image sequence timestamps (index / fps)")
      ->default_str("60")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--record", a->record, "also write the packets to this SSL log file (.gz: compressed)");
  cmd->add_option("--jsonl", a->jsonl, "also write one canonical-JSON SSL_WrapperPacket per line here");
  cmd->add_flag("--no-publish", a->no_publish, "do not multicast the packets");
  cmd->add_flag("--no-guessed-ids", a->no_guessed_ids,
                "leave out robots whose id is a guess (a side blob missing and no track or teammate settles it)");
  cmd->add_option("--multicast-group", a->multicast_group, "vision multicast group")
      ->default_str("224.5.23.2");
  cmd->add_option("--multicast-port", a->multicast_port, "vision multicast port")->default_str("10006");
  cmd->add_option("--multicast-interface", a->multicast_interface,
                  "local IPv4 address of the interface to publish on (default: by route)");
  cmd->add_option("--debug-dir", a->debug_dir, "write the inspection views of one frame here");
  cmd->add_option("--debug-frame", a->debug_frame, "index of the frame to inspect (default 0)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", a->threads, "pipeline threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--backend", a->backend, "pixel pipeline backend: auto|cpu|opencl (auto: an OpenCL GPU if there is one, else the CPU reference)")
      ->default_str("auto");
  cmd->add_option("--opencl-platform", a->opencl_platform, "OpenCL platform: index or name substring");
  cmd->add_option("--opencl-device", a->opencl_device, "OpenCL device: index or name substring");
  cmd->add_option("--max-frames", a->max_frames, "stop after this many frames")->check(CLI::NonNegativeNumber);
  cmd->add_option("--robot-height", a->robot_height, "robot height of both teams in mm (default 140)")
      ->check(CLI::Range(50.0, 300.0));
  cmd->add_option("--robot-height-yellow", a->robot_height_yellow, "robot height of the yellow team in mm")
      ->check(CLI::Range(50.0, 300.0));
  cmd->add_option("--robot-height-blue", a->robot_height_blue, "robot height of the blue team in mm")
      ->check(CLI::Range(50.0, 300.0));
  cmd->add_flag("--realtime", a->realtime,
                "files and videos: deliver frames at their own rate, as a camera would (latest frame wins)");
  cmd->add_option("--camera-set", a->camera_set,
                  "camera setting Name=Value by GenICam feature name (repeatable, applied in order), "
                  "e.g. ExposureTime=4000 Gain=0");
  cmd->add_option("--status-interval", a->status_interval,
                  "seconds between status lines of a live run (default 5; 0: none)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--quiet", a->quiet, "no progress or status lines on the terminal");
  cmd->add_option("--http", a->http,
                  "a live run: host serve's console in the browser here, IPv4ADDR:PORT (e.g. 127.0.0.1:8080; "
                  "port 0: a free one)")
      ->each([a](const std::string&) { a->http_given = true; });

  return [a] {
    installSignalHandlers();  // first: every thread started later inherits the blocked signals
    // Validate the Bayer name up front so a typo fails before any work.
    bayerFormatFromName(a->bayer, "--bayer");
    processorOptions(*a);
    if (!a->source.empty()) return runOnSource(*a);
    if (!a->geometry.empty())
      throw InputError("command line", "--geometry is only used with --source (the synthetic scene has its own)");
    return runSynthetic(*a);
  };
}

}  // namespace dv::app

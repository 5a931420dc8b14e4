#include "app/console_api.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "app/config_edit.h"
#include "app/console_http.h"
#include "app/console_image.h"
#include "app/console_state.h"
#include "core/error.h"
#include "geometry/proto_json.h"
// Last: it brings <resolv.h>, whose _res macro breaks Eigen headers included after it.
#include <httplib.h>

namespace dv::app {

namespace {

using nlohmann::json;

json detectionJson(const ssl::SSL_DetectionFrame& d) { return json::parse(toCanonicalJson(d)); }

json configValues(const SiteConfig& c) {
  const SiteRobotHeights& h = c.robot_heights;
  json teams = json::object();
  for (const auto& [name, mm] : h.teams) teams[name] = mm;
  json cameras = json::array();
  for (const SiteCamera& cam : c.cameras) {
    json settings = json::array();
    for (const CameraSetting& s : cam.settings) settings.push_back(s.name + "=" + s.value);
    cameras.push_back({{"id", cam.id}, {"source", cam.source}, {"settings", settings}});
  }
  return {{"robot_heights",
           {{"default", h.default_mm},
            {"yellow", h.yellow_mm ? json(*h.yellow_mm) : json()},
            {"blue", h.blue_mm ? json(*h.blue_mm) : json()},
            {"teams", teams}}},
          {"detector",
           {{"guessed_ids", c.detector.guessed_ids},
            {"tracking", c.detector.tracking},
            {"ball_radius", c.detector.ball_radius}}},
          {"cameras", cameras}};
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".console.tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    if (!out) throw InputError(path, "cannot write the config (via " + tmp + ")");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw InputError(path, "cannot replace the config: " + ec.message());
}

// dotvision run has no config file: its settings are its command line.
bool refusedWithoutConfig(const ConsoleState& state, httplib::Response& res) {
  if (!state.configPath().empty()) return false;
  sendError(res, 409, "this process has no config file to change (dotvision run takes its settings from the "
                      "command line; dotvision serve SITE.yaml has one)");
  return true;
}

// The new config text goes the SIGHUP way: validated as a whole (a bad one
// is refused with its errors and the running config stays), then applied
// by the main loop; saved to the file only when asked.
void applyConfigText(ConsoleState& state, const httplib::Request& req, httplib::Response& res,
                     const std::string& text, bool layout_kept) {
  SiteConfig next;
  try {
    next = parseSiteConfig(text, state.configPath());
  } catch (const InputError& e) {
    sendJson(res, {{"applied", false}, {"error", e.what()}}, 400);
    return;
  }
  const ConsoleState::ReloadResult r = state.reload(next, text, 15);
  if (!r.applied) {
    sendError(res, 503, "serve's main loop did not take the new config within 15 s; it may still apply it");
    return;
  }
  json out = {{"applied", true}, {"notes", r.notes}, {"saved", false}, {"layout_kept", layout_kept}};
  if (req.has_param("save") && req.get_param_value("save") != "0") {
    try {
      writeFileAtomically(state.configPath(), text);
      out["saved"] = true;
    } catch (const InputError& e) {
      out["save_error"] = e.what();
      sendJson(res, out, 500);
      return;
    }
  }
  sendJson(res, out);
}

}  // namespace

void addConsoleApi(httplib::Server& server, ConsoleState& state) {
  addCalibrationApi(server, state);
  addLogApi(server, state);
  addColorsApi(server, state);
  server.Get("/api/status", [&state](const httplib::Request&, httplib::Response& res) {
    sendJson(res, state.status());
  });

  server.Get("/api/geometry", [&state](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(toCanonicalJson(toProto(state.geometry())), "application/json");
  });

  // The cameras this process runs: image size and footprint on the field.
  server.Get("/api/cameras", [&state](const httplib::Request&, httplib::Response& res) {
    json cams = json::array();
    const Geometry geometry = state.geometry();
    for (const auto& f : state.feeds()) {
      json c = {{"camera_id", f->cameraId()}};
      if (const CameraCalibration* cal = geometry.camera(f->cameraId())) {
        c["image_width"] = cal->image_width;
        c["image_height"] = cal->image_height;
        json fp = json::array();
        for (const FieldMm& p : cameraFootprint(*cal)) fp.push_back({p.x, p.y});
        c["footprint"] = fp;
      }
      cams.push_back(c);
    }
    sendJson(res, {{"cameras", cams}});
  });

  // The newest detection frame of every camera (null before the first).
  server.Get("/api/detections", [&state](const httplib::Request&, httplib::Response& res) {
    json cams = json::array();
    ssl::SSL_DetectionFrame d;
    for (const auto& f : state.feeds())
      cams.push_back({{"camera_id", f->cameraId()}, {"detection", f->detection(d) ? detectionJson(d) : json()}});
    sendJson(res, {{"cameras", cams}});
  });

  server.Get(R"(/api/cameras/(\d+)/snapshot\.(png|jpg))", [&state](const httplib::Request& req,
                                                                   httplib::Response& res) {
    CameraFeed* feed = cameraOf(state, req, res);
    if (!feed) return;
    std::string why;
    const auto layers = parseSnapshotLayers(req.has_param("layer") ? req.get_param_value("layer") : "raw", why);
    if (!layers) return sendError(res, 400, why);
    double width = 960;
    if (!numberParam(req, res, "width", 16, 8192, width)) return;
    const Geometry geometry = state.geometry();
    SnapshotSource source;
    bool fresh = false;
    if (layers->needsPipeline()) {
      // The console's own pipeline run (console_layers.h), rate-limited per camera.
      if (!state.layers().take(*feed, geometry.field, layers->base, source, fresh, why)) return sendError(res, 503, why);
    } else {
      if (!feed->snapshot(2.0, source.frame, source.detection, fresh))
        return sendError(res, 503, "camera " + std::to_string(feed->cameraId()) + " has processed no frame yet");
      if (const CameraCalibration* cal = geometry.camera(feed->cameraId())) source.calibration = *cal;
    }
    const cv::Mat img = renderSnapshot(source, geometry.field, *layers, static_cast<int>(width));
    const Frame& frame = source.frame;
    const bool png = req.matches[2].str() == "png";
    std::vector<uchar> bytes;
    if (!cv::imencode(png ? ".png" : ".jpg", img, bytes, png ? std::vector<int>{} :
                      std::vector<int>{cv::IMWRITE_JPEG_QUALITY, 80}))
      return sendError(res, 500, "the image could not be encoded");
    res.set_header("Cache-Control", "no-store");
    res.set_header("X-Dotvision-Frame", std::to_string(frame.index));
    res.set_header("X-Dotvision-Fresh", fresh ? "1" : "0");
    res.set_header("X-Dotvision-Source-Size", std::to_string(frame.image.cols) + "x" + std::to_string(frame.image.rows));
    res.set_content(std::string(bytes.begin(), bytes.end()), png ? "image/png" : "image/jpeg");
  });

  // The rectified grid the grid layers are drawn on: grid px (gx, gy), cell
  // centers at integers, lie at field mm (x0 + gx * mm_per_cell, y0 - gy * mm_per_cell)
  // on the plane z = plane_height_mm.
  server.Get(R"(/api/cameras/(\d+)/grid)", [&state](const httplib::Request& req, httplib::Response& res) {
    CameraFeed* feed = cameraOf(state, req, res);
    if (!feed) return;
    RectifiedGrid grid;
    double plane = 0;
    std::string why;
    if (!state.layers().grid(*feed, state.geometry().field, grid, plane, why)) return sendError(res, 503, why);
    sendJson(res, {{"camera_id", feed->cameraId()}, {"width", grid.width}, {"height", grid.height},
                   {"x0_mm", grid.x0}, {"y0_mm", grid.y0}, {"mm_per_cell", grid.scale}, {"plane_height_mm", plane}});
  });

  // A pixel of camera ID's full-size image -> the field point it sees at
  // height z (default 0), for the camera page's hover.
  server.Get(R"(/api/cameras/(\d+)/field_point)", [&state](const httplib::Request& req, httplib::Response& res) {
    CameraFeed* feed = cameraOf(state, req, res);
    if (!feed) return;
    const Geometry geometry = state.geometry();
    const CameraCalibration* cal = geometry.camera(feed->cameraId());
    if (!cal) return sendError(res, 404, "camera " + std::to_string(feed->cameraId()) + " has no calibration");
    double u = 0, v = 0, z = 0;
    if (!req.has_param("u") || !req.has_param("v")) return sendError(res, 400, "give the pixel as ?u=..&v=..");
    if (!numberParam(req, res, "u", -1e5, 1e5, u) || !numberParam(req, res, "v", -1e5, 1e5, v) ||
        !numberParam(req, res, "z", -1000, 1000, z))
      return;
    const auto p = CameraModel(*cal).imageToField({u, v}, z);
    if (!p) return sendJson(res, {{"x", nullptr}, {"y", nullptr}, {"why", "the pixel's ray misses the field"}});
    sendJson(res, {{"x", p->x}, {"y", p->y}, {"z", z}});
  });

  server.Get("/api/config", [&state](const httplib::Request& req, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    if (req.has_param("format") && req.get_param_value("format") == "json")
      return sendJson(res, {{"path", state.configPath()}, {"text", state.configText()},
                            {"values", configValues(state.config())}});
    res.set_content(state.configText(), "application/yaml");
  });

  // Config changes one at a time, so an edit's read-modify-write holds.
  static std::mutex edit_mutex;
  server.Put("/api/config", [&state](const httplib::Request& req, httplib::Response& res) {
    std::lock_guard<std::mutex> lock(edit_mutex);
    if (refusedWithoutConfig(state, res)) return;
    applyConfigText(state, req, res, req.body, true);
  });
  // {"robot_heights.default": 130, "detector.tracking": false}: the keys
  // changed in the running config's text (config_edit.h), then as PUT.
  server.Patch("/api/config", [&state](const httplib::Request& req, httplib::Response& res) {
    std::lock_guard<std::mutex> lock(edit_mutex);
    if (refusedWithoutConfig(state, res)) return;
    json edits;
    try {
      edits = json::parse(req.body);
    } catch (const json::exception& e) {
      return sendError(res, 400, std::string("the body is not JSON: ") + e.what());
    }
    if (!edits.is_object() || edits.empty())
      return sendError(res, 400, "expected a JSON object of \"dotted.key\": value, e.g. {\"robot_heights.default\": 130}");
    std::vector<ConfigEdit> list;
    for (const auto& [key, value] : edits.items()) {
      if (value.is_object() || value.is_array())
        return sendError(res, 400, "key '" + key + "': expected a number, true/false, null or a string");
      list.push_back({key, value.dump()});
    }
    ConfigEditResult edited;
    try {
      edited = editConfigText(state.configText(), list, state.configPath());
    } catch (const InputError& e) {
      return sendJson(res, {{"applied", false}, {"error", e.what()}}, 400);
    }
    applyConfigText(state, req, res, edited.text, edited.layout_kept);
  });
}

}  // namespace dv::app

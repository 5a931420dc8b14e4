// The console's calibration routes and its log:
//   POST /api/cameras/ID/calibrate            (token) start a run on the newest frame;
//        body (optional JSON): {"region": "x<0", "near": "X,Y" | [X,Y], "camera_height": MM,
//        "num_cameras": N, "points": [[X,Y,U,V], ...] (four or more: the four-point mode;
//        a set that cannot fix a pose is refused with 400 at once)}
//   GET  /api/cameras/ID/calibration          its state, report and the lines found
//   GET  /api/cameras/ID/calibration/overlay.jpg?width=W
//   POST /api/cameras/ID/calibration/accept   (token) body {"publisher": "ADDR[:PORT]"} optional
//   POST /api/cameras/ID/calibration/reject   (token)
//   GET  /api/log?after=SEQ                    serve's recent log lines
#include <algorithm>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "app/console_http.h"
#include "app/console_state.h"
#include "app/console_host.h"
#include "core/error.h"
// Last: it brings <resolv.h>, whose _res macro breaks Eigen headers included after it.
#include <httplib.h>

namespace dv::app {

namespace {

using nlohmann::json;

// The run's request from the body; throws InputError("calibrate request", ...).
CalibrationRequest calibrationRequest(const std::string& body, uint32_t camera_id, const FieldModel& field) {
  const std::string source = "calibrate request";
  CalibrationRequest req;
  req.camera_id = camera_id;
  req.source = "camera " + std::to_string(camera_id) + "'s newest frame";
  if (body.find_first_not_of(" \t\r\n") == std::string::npos) return req;
  json j;
  try {
    j = json::parse(body);
  } catch (const json::exception& e) {
    throw InputError(source, std::string("the body is not JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError(source, "expected a JSON object, e.g. {\"region\": \"x<0\"}");
  for (const auto& [key, value] : j.items()) {
    if (key == "region" && value.is_string() && !value.get<std::string>().empty()) {
      req.hint = parseRegionHint(value.get<std::string>(), field, source);
    } else if (key == "near" && value.is_string() && !value.get<std::string>().empty()) {
      req.hint = parseNearHint(value.get<std::string>(), field, source);
    } else if (key == "near" && value.is_array() && value.size() == 2 && value[0].is_number() && value[1].is_number()) {
      req.hint = parseNearHint(std::to_string(value[0].get<double>()) + "," + std::to_string(value[1].get<double>()),
                               field, source);
    } else if (key == "camera_height" && value.is_number() && value.get<double>() > 0) {
      req.camera_height_mm = value.get<double>();
    } else if (key == "num_cameras" && value.is_number_unsigned()) {
      req.num_cameras = value.get<unsigned>();
    } else if (key == "points" && value.is_array()) {
      for (const json& p : value) {
        if (!p.is_array() || p.size() != 4 || !std::all_of(p.begin(), p.end(), [](const json& x) { return x.is_number(); }))
          throw InputError(source, "points: expected [[X, Y, U, V], ...] (field mm, image px), got " + p.dump());
        req.points.push_back({{p[0].get<double>(), p[1].get<double>(), 0.0}, {p[2].get<double>(), p[3].get<double>()}});
      }
      if (req.points.size() < 4)
        throw InputError(source, "points: four or more are needed, got " + std::to_string(req.points.size()));
    } else if (!value.is_null() && !(value.is_string() && value.get<std::string>().empty())) {
      throw InputError(source, "'" + key + "': " + value.dump() +
                                   " is not understood (known: region, near, camera_height, num_cameras, points)");
    }
  }
  return req;
}

std::string bodyPublisher(const std::string& body) {
  if (body.find_first_not_of(" \t\r\n") == std::string::npos) return "";
  json j;
  try {
    j = json::parse(body);
  } catch (const json::exception& e) {
    throw InputError("accept request", std::string("the body is not JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError("accept request", "expected a JSON object, e.g. {\"publisher\": \"10.0.0.5\"}");
  if (!j.contains("publisher")) return "";
  if (!j["publisher"].is_string()) throw InputError("accept request", "publisher: expected \"ADDR\" or \"ADDR:PORT\"");
  return j["publisher"].get<std::string>();
}

}  // namespace

void addCalibrationApi(httplib::Server& server, ConsoleState& state) {
  server.Post(R"(/api/cameras/(\d+)/calibrate)", [&state](const httplib::Request& req, httplib::Response& res) {
    CameraFeed* feed = cameraOf(state, req, res);
    if (!feed) return;
    const FieldModel field = state.geometry().field;
    CalibrationRequest request;
    try {
      request = calibrationRequest(req.body, feed->cameraId(), field);
    } catch (const InputError& e) {
      return sendError(res, 400, e.what());
    }
    Frame frame;
    ssl::SSL_DetectionFrame detection;
    bool fresh = false;
    if (!feed->snapshot(2.0, frame, detection, fresh))
      return sendError(res, 503, "camera " + std::to_string(feed->cameraId()) + " has processed no frame yet");
    // Points that cannot fix a pose are refused at once, with the reason.
    if (!request.points.empty()) {
      const int w = frame.image.cols, h = frame.image.rows;
      for (const PointCorrespondence& p : request.points)
        if (!(p.image.u >= 0 && p.image.v >= 0 && p.image.u <= w - 1 && p.image.v <= h - 1))
          return sendError(res, 400, "points: (" + std::to_string(p.image.u) + ", " + std::to_string(p.image.v) +
                                         ") lies outside the " + std::to_string(w) + "x" + std::to_string(h) + " image");
      if (const auto why = pointSetProblem(request.points, w, h))
        return sendError(res, 400, "points: they cannot fix a camera pose: " + *why);
    }
    if (!state.calibrations().start(frame, field, request))
      return sendError(res, 409, "camera " + std::to_string(feed->cameraId()) + ": a calibration is still running");
    sendJson(res, state.calibrations().describe(feed->cameraId()), 202);
  });

  server.Get(R"(/api/cameras/(\d+)/calibration)", [&state](const httplib::Request& req, httplib::Response& res) {
    CameraFeed* feed = cameraOf(state, req, res);
    if (!feed) return;
    sendJson(res, state.calibrations().describe(feed->cameraId()));
  });

  server.Get(R"(/api/cameras/(\d+)/calibration/overlay\.jpg)", [&state](const httplib::Request& req,
                                                                        httplib::Response& res) {
    CameraFeed* feed = cameraOf(state, req, res);
    if (!feed) return;
    double width = 960;
    if (!numberParam(req, res, "width", 16, 8192, width)) return;
    const cv::Mat img = state.calibrations().overlay(feed->cameraId(), state.geometry().field, int(width));
    if (img.empty()) return sendError(res, 404, "camera " + std::to_string(feed->cameraId()) + " has no calibration run");
    std::vector<uchar> bytes;
    if (!cv::imencode(".jpg", img, bytes, {cv::IMWRITE_JPEG_QUALITY, 85}))
      return sendError(res, 500, "the image could not be encoded");
    res.set_header("Cache-Control", "no-store");
    res.set_content(std::string(bytes.begin(), bytes.end()), "image/jpeg");
  });

  server.Post(R"(/api/cameras/(\d+)/calibration/accept)", [&state](const httplib::Request& req,
                                                                   httplib::Response& res) {
    CameraFeed* feed = cameraOf(state, req, res);
    if (!feed) return;
    std::string publisher, why;
    try {
      publisher = bodyPublisher(req.body);
    } catch (const InputError& e) {
      return sendError(res, 400, e.what());
    }
    const std::optional<CameraCalibration> cal = state.calibrations().acceptable(feed->cameraId(), why);
    if (!cal) return sendError(res, 409, why);
    const CameraCalibration c = *cal;
    const ConsoleState::TaskResult r = state.onMainLoop(
        [c, publisher](ConsoleHost& runtime) { return runtime.setCalibration(c, publisher); }, 15);
    if (!r.applied) return sendError(res, 503, "serve's main loop did not take the calibration within 15 s");
    if (!r.error.empty()) return sendError(res, 400, r.error);
    state.setCameraCalibration(c);
    state.calibrations().settle(feed->cameraId(), true);
    sendJson(res, {{"accepted", true}, {"notes", r.notes}});
  });

  server.Post(R"(/api/cameras/(\d+)/calibration/reject)", [&state](const httplib::Request& req,
                                                                   httplib::Response& res) {
    CameraFeed* feed = cameraOf(state, req, res);
    if (!feed) return;
    if (!state.calibrations().settle(feed->cameraId(), false))
      return sendError(res, 409, "camera " + std::to_string(feed->cameraId()) + " has no finished calibration to reject");
    sendJson(res, {{"rejected", true}});
  });
}

void addLogApi(httplib::Server& server, ConsoleState& state) {
  server.Get("/api/log", [&state](const httplib::Request& req, httplib::Response& res) {
    double after = 0;
    if (!numberParam(req, res, "after", 0, 1e18, after)) return;
    json lines = json::array();
    if (const LogRing* ring = state.logRing())
      for (const LogRing::Line& l : ring->since(uint64_t(after)))
        lines.push_back({{"seq", l.seq}, {"t", l.t_unix}, {"text", l.text}, {"warning", l.warning}});
    sendJson(res, {{"lines", lines}});
  });
}

}  // namespace dv::app

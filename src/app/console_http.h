#pragma once
// What the console's API handlers share: JSON replies and errors, query
// numbers, the camera a path names.
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace httplib {
struct Request;
struct Response;
class Server;
}  // namespace httplib

namespace dv::app {

class CameraFeed;
class ConsoleState;

void sendJson(httplib::Response& res, const nlohmann::json& j, int status = 200);
void sendError(httplib::Response& res, int status, const std::string& what);
// A query parameter as a number in [lo, hi] into `value` (left alone when
// absent); false (and a 400 sent) when it is given but not such a number.
bool numberParam(const httplib::Request& req, httplib::Response& res, const char* name, double lo, double hi,
                 double& value);
// The camera of the path's first match; null (and a 404 sent) when none runs.
CameraFeed* cameraOf(ConsoleState& state, const httplib::Request& req, httplib::Response& res);

// The calibration routes and the log's (console_calibration_api.cpp), the colors' (console_colors_api.cpp).
void addCalibrationApi(httplib::Server& server, ConsoleState& state);
void addLogApi(httplib::Server& server, ConsoleState& state);
void addColorsApi(httplib::Server& server, ConsoleState& state);

}  // namespace dv::app

#include "app/console_http.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "app/console_state.h"
// Last: it brings <resolv.h>, whose _res macro breaks Eigen headers included after it.
#include <httplib.h>

namespace dv::app {

using nlohmann::json;

void sendJson(httplib::Response& res, const json& j, int status) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(j.dump(), "application/json");
}

void sendError(httplib::Response& res, int status, const std::string& what) { sendJson(res, {{"error", what}}, status); }

bool numberParam(const httplib::Request& req, httplib::Response& res, const char* name, double lo, double hi,
                 double& value) {
  if (!req.has_param(name)) return true;
  const std::string text = req.get_param_value(name);
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi) {
    sendError(res, 400, std::string("parameter '") + name + "': expected a number in " + std::to_string(lo) +
                            ".." + std::to_string(hi) + ", got '" + text + "'");
    return false;
  }
  value = v;
  return true;
}

CameraFeed* cameraOf(ConsoleState& state, const httplib::Request& req, httplib::Response& res) {
  const unsigned long id = std::stoul(req.matches[1].str());
  CameraFeed* feed = id <= 255 ? state.feed(uint32_t(id)) : nullptr;
  if (!feed) sendError(res, 404, "no camera " + req.matches[1].str() + " runs here");
  return feed;
}

}  // namespace dv::app

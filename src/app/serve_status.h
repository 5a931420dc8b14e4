#pragma once
// serve's status document: the config, the game controller's team names and
// every camera's status record. Written to --status-file once a second and
// served by the console as GET /api/status.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "live/camera_status.h"
#include "net/referee_listener.h"

namespace dv::app {

nlohmann::json serveStatusJson(const std::vector<CameraStatus>& cameras, const std::string& config_path,
                               const RefereeSnapshot& referee);

}  // namespace dv::app

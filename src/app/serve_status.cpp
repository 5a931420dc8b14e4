#include "app/serve_status.h"

namespace dv::app {

nlohmann::json serveStatusJson(const std::vector<CameraStatus>& cameras, const std::string& config_path,
                               const RefereeSnapshot& referee) {
  nlohmann::json j;
  j["config"] = config_path;
  j["teams"] = {{"yellow", referee.yellow_name}, {"blue", referee.blue_name}};
  j["cameras"] = nlohmann::json::array();
  for (const CameraStatus& c : cameras) j["cameras"].push_back(toJson(c));
  return j;
}

}  // namespace dv::app

#include "app/run_console.h"

#include "app/camera_runner.h"
#include "app/serve_status.h"
#include "core/error.h"

namespace dv::app {

RunConsole::RunConsole(CameraRunner& runner, const Geometry& geometry, PacketOutputs& outputs,
                       const std::string& http, ConsoleServer::LogFn log)
    : runner_(runner), geometry_(geometry), outputs_(outputs), log_(std::move(log)) {
  config_.console.http = http;
  server_ = makeConsole(*this, &http, log_);
}

RunConsole::~RunConsole() {
  if (server_) server_->stop();
}

void RunConsole::start() {
  if (!server_) return;
  server_->start();
  log_("console: " + server_->url() + "#token=" + server_->token() + " (changes need the token " +
       server_->token() + ")");
}

void RunConsole::service() {
  if (server_) server_->service(*this);
}

void RunConsole::setStatus(const CameraStatus& status) {
  if (server_) server_->setStatus(serveStatusJson({status}, "", RefereeSnapshot{}));
}

std::vector<std::string> RunConsole::reload(const SiteConfig&) {
  throw InputError("dotvision run", "has no config file to change: its settings are its command line");
}

std::vector<std::string> RunConsole::setCalibration(const CameraCalibration& c, const std::string& publisher) {
  if (c.camera_id != runner_.cameraId())
    throw InputError("camera " + std::to_string(c.camera_id), "no camera of this id runs here");
  std::vector<std::string> notes = useCalibration(runner_, geometry_, outputs_, c);
  if (!publisher.empty()) notes.push_back("not sent to a geometry publisher: dotvision run sends none");
  return notes;
}

}  // namespace dv::app

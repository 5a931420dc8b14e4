#include "app/console_state.h"

#include <chrono>

#include "app/console_host.h"
#include "core/error.h"

namespace dv::app {

ConsoleState::ConsoleState(const Geometry& geometry, const std::vector<uint32_t>& camera_ids,
                           const SiteConfig& config, std::string config_text)
    : geometry_(geometry), config_path_(config.path), config_(config), config_text_(std::move(config_text)) {
  for (uint32_t id : camera_ids) feeds_.push_back(std::make_shared<CameraFeed>(id));
  status_ = {{"config", config.path}, {"cameras", nlohmann::json::array()}};
}

void ConsoleState::setStatus(nlohmann::json status) {
  std::lock_guard<std::mutex> lock(mutex_);
  status_ = std::move(status);
}

nlohmann::json ConsoleState::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

CameraFeed* ConsoleState::feed(uint32_t camera_id) {
  for (auto& f : feeds_)
    if (f->cameraId() == camera_id) return f.get();
  return nullptr;
}

std::shared_ptr<CameraFeed> ConsoleState::sharedFeed(uint32_t camera_id) {
  for (auto& f : feeds_)
    if (f->cameraId() == camera_id) return f;
  return nullptr;
}

std::string ConsoleState::configText() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return config_text_;
}

SiteConfig ConsoleState::config() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return config_;
}

Geometry ConsoleState::geometry() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return geometry_;
}

void ConsoleState::setCameraCalibration(const CameraCalibration& c) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (CameraCalibration& old : geometry_.cameras)
    if (old.camera_id == c.camera_id) old = c;
}

ConsoleState::TaskResult ConsoleState::onMainLoop(Task task, double timeout_s) {
  auto job = std::make_shared<Job>();
  job->task = std::move(task);
  std::future<std::vector<std::string>> done = job->notes.get_future();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    jobs_.push_back(job);
  }
  TaskResult r;
  if (done.wait_for(std::chrono::duration<double>(timeout_s)) != std::future_status::ready) return r;
  try {
    r.notes = done.get();
    r.applied = true;
  } catch (const InputError& e) {
    r.applied = true;
    r.error = e.what();
  } catch (const std::future_error&) {  // serve stopped before taking it
  }
  return r;
}

ConsoleState::ReloadResult ConsoleState::reload(const SiteConfig& next, const std::string& text, double timeout_s) {
  const TaskResult r = onMainLoop(
      [this, next, text](ConsoleHost& runtime) {
        std::vector<std::string> notes = runtime.reload(next);
        std::lock_guard<std::mutex> lock(mutex_);
        if (next.console.http != config_.console.http || next.console.token_file != config_.console.token_file)
          notes.push_back("console settings (http, token_file) take effect when serve restarts");
        const SiteConsole console = config_.console;  // the console running is the one started
        config_ = next;
        config_.console = console;
        config_text_ = text;
        return notes;
      },
      timeout_s);
  return r;
}

void ConsoleState::service(ConsoleHost& runtime) {
  for (;;) {
    std::shared_ptr<Job> job;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (jobs_.empty()) return;
      job = jobs_.front();
      jobs_.pop_front();
    }
    try {
      job->notes.set_value(job->task(runtime));
    } catch (const InputError&) {
      job->notes.set_exception(std::current_exception());
    }
  }
}

}  // namespace dv::app

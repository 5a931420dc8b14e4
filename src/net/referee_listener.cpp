#include "net/referee_listener.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "net/multicast.h"

namespace dv {
namespace {
constexpr double kPollInterval_s = 0.1;  // how soon the thread sees stop
}  // namespace

RefereeListener::RefereeListener(RefereeListenerOptions options)
    : rx_(std::make_unique<MulticastReceiver>(options.group, options.port, options.interface_addr)),
      name_(rx_->name()) {
  thread_ = std::thread([this] { run(); });
}

RefereeListener::~RefereeListener() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

RefereeSnapshot RefereeListener::snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return state_;
}

RefereeListenerStats RefereeListener::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

bool RefereeListener::waitForDatagrams(uint64_t datagrams, double timeout_s) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return handled_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                           [&] { return stats_.datagrams >= datagrams; });
}

void RefereeListener::run() {
  std::string payload, sender;
  while (!stop_) {
    if (rx_->receive(kPollInterval_s, payload, &sender)) handle(payload, sender);
  }
}

void RefereeListener::warnOnce(const std::string& reason) {
  if (warned_.insert(reason).second)
    spdlog::warn("{}: dropping referee datagrams: {} (warned once; they are counted)", name_, reason);
}

std::string parseRefereeDatagram(const std::string& payload, dv::ssl::Referee& packet) {
  if (!packet.ParsePartialFromString(payload)) return "not a Referee message (the bytes do not decode)";
  if (!packet.IsInitialized()) {
    return "Referee message without required field(s) " + packet.InitializationErrorString();
  }
  return "";
}

void RefereeListener::handle(const std::string& payload, const std::string& sender) {
  const std::string problem = parseRefereeDatagram(payload, packet_);
  if (!problem.empty()) {
    warnOnce(problem);
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.datagrams;
    ++stats_.malformed;
    stats_.malformed_reasons = warned_.size();
    handled_.notify_all();
    return;
  }

  RefereeSnapshot next;
  next.valid = true;
  next.yellow_name = packet_.yellow().name();
  next.blue_name = packet_.blue().name();
  next.stage = packet_.stage();
  next.command = packet_.command();
  next.command_counter = packet_.command_counter();
  next.has_blue_side = packet_.has_blue_team_on_positive_half();
  next.blue_on_positive_half = packet_.blue_team_on_positive_half();
  next.packet_time = double(packet_.packet_timestamp()) * 1e-6;
  next.sender = sender;
  next.source_identifier = packet_.source_identifier();

  std::lock_guard<std::mutex> lock(mutex_);
  const RefereeSnapshot& prev = state_;
  const bool teams_changed = !prev.valid || prev.yellow_name != next.yellow_name ||
                             prev.blue_name != next.blue_name || prev.has_blue_side != next.has_blue_side ||
                             prev.blue_on_positive_half != next.blue_on_positive_half;
  if (teams_changed) {
    const bool swapped = prev.valid && prev.yellow_name == next.blue_name &&
                         prev.blue_name == next.yellow_name && prev.yellow_name != prev.blue_name;
    spdlog::info("{}: {}yellow \"{}\", blue \"{}\"{} (game controller {})", name_,
                 !prev.valid ? "teams: "
                 : swapped   ? "teams swapped colors: "
                             : "teams changed: ",
                 next.yellow_name, next.blue_name,
                 next.has_blue_side ? (next.blue_on_positive_half ? ", blue on the positive half"
                                                                  : ", blue on the negative half")
                                    : "",
                 sender);
    next.changes = prev.changes + 1;
  } else {
    next.changes = prev.changes;
  }
  state_ = std::move(next);
  ++stats_.datagrams;
  ++stats_.accepted;
  changes_.store(state_.changes, std::memory_order_release);
  handled_.notify_all();
}

}  // namespace dv

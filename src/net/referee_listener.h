#pragma once
// Listens to the game controller's referee messages (dv::ssl::Referee on
// 224.5.23.1:10003) in a thread of its own and keeps the newest state: the
// team names, which color plays on which half, the stage and command. A
// consumer polls changeCount() once per frame (one atomic load) and takes a
// snapshot() only when it moved, so a team change or a color swap applies at
// its next frame. Bad datagrams are counted and warned about once per
// distinct reason; they never stop the listener.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "dotvision/ssl_referee.pb.h"

namespace dv {

class MulticastReceiver;

struct RefereeListenerOptions {
  std::string group = "224.5.23.1";  // the league's referee group
  uint16_t port = 10003;
  std::string interface_addr;  // local IPv4 address to join on ("" = default interface)
};

// The newest referee state, copied out under the listener's lock.
struct RefereeSnapshot {
  bool valid = false;                  // false until the first good packet
  std::string yellow_name, blue_name;  // as the game controller spells them ("" = not typed yet)
  dv::ssl::Referee::Stage stage = dv::ssl::Referee::NORMAL_FIRST_HALF_PRE;
  dv::ssl::Referee::Command command = dv::ssl::Referee::HALT;
  uint32_t command_counter = 0;
  bool has_blue_side = false;  // the packet said which half blue plays on
  bool blue_on_positive_half = false;
  double packet_time = 0;         // Unix s (the packet's own time stamp)
  std::string sender;             // "a.b.c.d:port"
  std::string source_identifier;  // the game controller's id, "" if none
  uint64_t changes = 0;           // see RefereeListener::changeCount()
};

struct RefereeListenerStats {
  uint64_t datagrams = 0;          // received on the group
  uint64_t accepted = 0;           // parsed as a complete Referee message
  uint64_t malformed = 0;          // dropped: not a Referee message, or one missing required fields
  uint64_t malformed_reasons = 0;  // distinct reasons among them (each warned about once)
};

// Decodes one datagram into `packet`: "" when it is a complete Referee
// message, else why not (what the listener drops and counts).
std::string parseRefereeDatagram(const std::string& payload, dv::ssl::Referee& packet);

class RefereeListener {
 public:
  // Joins the group and starts the thread. Throws InputError naming
  // "udp <group>:<port>" when the socket cannot be set up.
  explicit RefereeListener(RefereeListenerOptions options = {});
  ~RefereeListener();
  RefereeListener(const RefereeListener&) = delete;
  RefereeListener& operator=(const RefereeListener&) = delete;

  RefereeSnapshot snapshot() const;
  // Counts team changes: the first packet, a new name for either color, a
  // color swap, a change of the half blue plays on. Stage and command
  // changes do not count (they come every few seconds and change no height).
  uint64_t changeCount() const { return changes_.load(std::memory_order_acquire); }
  RefereeListenerStats stats() const;
  // Waits until at least `datagrams` datagrams were handled (good or bad),
  // or timeout_s passed; true if reached. For tests and start-up.
  bool waitForDatagrams(uint64_t datagrams, double timeout_s) const;
  const std::string& name() const { return name_; }

 private:
  void run();
  void handle(const std::string& payload, const std::string& sender);
  void warnOnce(const std::string& reason);

  std::unique_ptr<MulticastReceiver> rx_;
  std::string name_;
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> changes_{0};
  mutable std::mutex mutex_;
  mutable std::condition_variable handled_;
  RefereeSnapshot state_;         // guarded by mutex_
  RefereeListenerStats stats_;    // guarded by mutex_
  std::set<std::string> warned_;  // reasons already logged (listener thread only)
  dv::ssl::Referee packet_;       // parse buffer (listener thread only)
  std::thread thread_;
};

}  // namespace dv

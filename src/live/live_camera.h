#pragma once
// One camera's two threads: capture (source -> FrameSlot) and processing
// (FrameSlot -> the caller's function). The capture thread owns every
// fault of the source: a skipped buffer is counted, a lost camera is
// reported once and retried every retry_interval_s with its settings, its
// return is reported with the length of the gap. Nothing here throws into
// the threads' owner; state and counters are read with counters().
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "io/camera_source.h"
#include "live/frame_slot.h"

namespace dv {

enum class SourceState { Starting, Running, NoFrames, Lost, Ended, Stopped };
const char* sourceStateName(SourceState s);

struct LiveCameraOptions {
  double retry_interval_s = 1;   // between reconnect attempts
  double stall_timeout_s = 1;    // a live camera silent this long is reported
  double grab_timeout_s = 0.1;   // one wait in the source (bounds stop latency)
};

struct LiveCounters {
  uint64_t frames_in = 0;    // frames the source delivered
  uint64_t processed = 0;    // frames the processing function ran on
  uint64_t dropped = 0;      // replaced in the slot before processing took them
  uint64_t skipped = 0;      // incomplete or corrupt buffers
  uint64_t losses = 0;       // times the camera was lost
  uint64_t reconnects = 0;   // times it came back
  uint64_t gap_frames = 0;   // frames missed while lost (gap x frame rate)
  SourceState state = SourceState::Starting;
  std::string last_problem;  // the newest warning's text
  double last_frame_unix = 0;
};

class LiveCamera {
 public:
  // process(frame, t_taken): runs on the processing thread for each frame
  // taken from the slot (t_taken: Unix s when it was taken). log(line):
  // state changes and faults, once each, from either thread.
  using ProcessFn = std::function<void(Frame& frame, double t_taken)>;
  using LogFn = std::function<void(const std::string& line)>;

  LiveCamera(std::string name, std::unique_ptr<CameraSource> source, ProcessFn process, LogFn log,
             LiveCameraOptions options = {});
  ~LiveCamera();
  LiveCamera(const LiveCamera&) = delete;
  LiveCamera& operator=(const LiveCamera&) = delete;

  void start();
  // Interrupts the source and joins both threads (the frame being processed
  // is finished first).
  void stop();
  // A finite source ended and its last frame was processed.
  bool ended() const { return ended_; }
  LiveCounters counters() const;
  CameraSource& source() { return *source_; }
  const std::string& name() const { return name_; }

 private:
  void captureLoop();
  void processLoop();
  void setState(SourceState s, const std::string& problem);

  std::string name_;
  std::unique_ptr<CameraSource> source_;
  ProcessFn process_;
  LogFn log_;
  LiveCameraOptions options_;
  FrameSlot slot_;
  std::thread capture_, processing_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> ended_{false};
  std::atomic<bool> ended_pending_{false};  // the source ended; set ended_ once drained
  mutable std::mutex mutex_;  // guards counters_ fields that are not atomic
  LiveCounters counters_;
};

}  // namespace dv

// The live flow without a camera: the latest-frame slot, a camera thread
// pair fed by a scripted source (drops when processing is slow, a lost
// camera retried and back with its gap counted, skipped buffers counted),
// paced file replay, and the health rules.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <deque>
#include <mutex>
#include <thread>

#include "io/camera_source.h"
#include "live/frame_slot.h"
#include "live/health_monitor.h"
#include "live/latency_window.h"
#include "live/live_camera.h"

namespace dv {
namespace {

double unixNow() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

Frame numbered(uint32_t i) {
  Frame f;
  f.image = cv::Mat(4, 4, CV_8UC1, cv::Scalar(i % 256));
  f.index = i;
  return f;
}

TEST(FrameSlot, TheLatestFrameWinsAndReplacingCountsAsADrop) {
  FrameSlot slot;
  Frame a = numbered(1), b = numbered(2), out;
  EXPECT_FALSE(slot.put(a));
  EXPECT_TRUE(slot.put(b));  // 1 was never taken
  ASSERT_TRUE(slot.take(out, 0.1));
  EXPECT_EQ(out.index, 2u);
  EXPECT_FALSE(slot.take(out, 0.01));  // empty: times out
  Frame c = numbered(3);
  slot.put(c);
  slot.close();
  ASSERT_TRUE(slot.take(out, 0.1));  // a frame left in a closed slot is still handed out
  EXPECT_EQ(out.index, 3u);
  EXPECT_FALSE(slot.take(out, 10));  // closed and empty: at once
}

TEST(LatencyWindow, PercentilesCoverOnlyTheLastMinute) {
  LatencyWindow w(100, 60);
  for (int i = 0; i < 50; ++i) w.add(0, 1000);        // old
  for (int i = 1; i <= 100; ++i) w.add(100, i);       // overwrites the ring
  std::vector<double> scratch;
  EXPECT_NEAR(w.percentile(100, 0.5, scratch), 50, 1);
  EXPECT_NEAR(w.percentile(100, 0.99, scratch), 99, 1);
  EXPECT_EQ(w.percentile(1000, 0.5, scratch), -1);  // nothing in the last minute
}

// A camera that delivers `period_s` apart, vanishes for frames in
// [lose_from, lose_until) (grab says Lost until reconnect is called after
// the outage), and hands out a corrupt buffer at `bad_at`.
class ScriptedCamera : public CameraSource {
 public:
  ScriptedCamera(double period_s, uint32_t total, uint32_t lose_from = 0, double outage_s = 0, uint32_t bad_at = 0)
      : period_(period_s), total_(total), lose_from_(lose_from), outage_(outage_s), bad_at_(bad_at) {}
  GrabStatus grab(Frame& f, double timeout_s, std::string& why) override {
    if (next_ >= total_) {
      std::this_thread::sleep_for(std::chrono::duration<double>(timeout_s));
      return GrabStatus::Timeout;
    }
    if (lost_) {
      why = "link down";
      return GrabStatus::Lost;
    }
    if (lose_from_ && next_ == lose_from_ && !was_lost_) {
      lost_ = was_lost_ = true;
      back_at_ = std::chrono::steady_clock::now() + std::chrono::milliseconds(static_cast<int>(outage_ * 1000));
      why = "link down";
      return GrabStatus::Lost;
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(period_));
    if (bad_at_ && next_ == bad_at_) {
      ++next_;
      why = "buffer 7 incomplete";
      return GrabStatus::Skipped;
    }
    f = numbered(next_);
    f.t_arrival = unixNow();
    f.t_capture = f.t_arrival;
    ++next_;
    return GrabStatus::Frame;
  }
  bool reconnect(std::string& why) override {
    ++reconnect_calls;
    if (std::chrono::steady_clock::now() < back_at_) {
      why = "no answer";
      return false;
    }
    lost_ = false;
    return true;
  }
  std::string describe() const override { return "scripted camera"; }
  bool live() const override { return true; }
  std::atomic<int> reconnect_calls{0};

 private:
  double period_;
  uint32_t total_, lose_from_;
  double outage_;
  uint32_t bad_at_;
  uint32_t next_ = 0;
  bool lost_ = false, was_lost_ = false;
  std::chrono::steady_clock::time_point back_at_{};
};

bool waitFor(const std::function<bool()>& done, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

TEST(LiveCamera, ProcessingSlowerThanTheCameraDropsOldFramesAndTakesTheNewest) {
  auto source = std::make_unique<ScriptedCamera>(0.002, 200);
  std::mutex m;
  std::vector<uint32_t> seen;
  std::vector<double> waits;
  LiveCamera cam("camera 0", std::move(source),
                 [&](Frame& f, double t_taken) {
                   std::this_thread::sleep_for(std::chrono::milliseconds(10));  // 5x slower than the camera
                   std::lock_guard<std::mutex> lock(m);
                   seen.push_back(f.index);
                   waits.push_back(t_taken - f.t_arrival);
                 },
                 nullptr);
  cam.start();
  ASSERT_TRUE(waitFor([&] { return cam.counters().frames_in >= 200; }, 60));
  ASSERT_TRUE(waitFor([&] { return cam.counters().processed + cam.counters().dropped >= 200; }, 10));
  cam.stop();
  const LiveCounters c = cam.counters();
  EXPECT_EQ(c.frames_in, 200u);
  EXPECT_EQ(c.processed + c.dropped, c.frames_in);  // every frame is either processed or counted
  EXPECT_GT(c.dropped, 50u);
  std::lock_guard<std::mutex> lock(m);
  for (size_t i = 1; i < seen.size(); ++i) EXPECT_GT(seen[i], seen[i - 1]);  // never an older frame
  // A frame waits at most about one processing time, never a queue of them.
  for (size_t i = 1; i < waits.size(); ++i) EXPECT_LT(waits[i], 0.5);
}

TEST(LiveCamera, ALostCameraIsRetriedReportedOnceAndCountedWhenBack) {
  auto source = std::make_unique<ScriptedCamera>(0.005, 120, 40, 0.4, 80);
  ScriptedCamera* raw = source.get();
  std::mutex m;
  std::vector<std::string> log;
  LiveCameraOptions opt;
  opt.retry_interval_s = 0.1;
  LiveCamera cam("camera 3", std::move(source), [](Frame&, double) {},
                 [&](const std::string& line) {
                   std::lock_guard<std::mutex> lock(m);
                   log.push_back(line);
                 },
                 opt);
  cam.start();
  ASSERT_TRUE(waitFor([&] { return cam.counters().frames_in >= 119; }, 60));
  cam.stop();
  const LiveCounters c = cam.counters();
  EXPECT_EQ(c.losses, 1u);
  EXPECT_EQ(c.reconnects, 1u);
  EXPECT_EQ(c.skipped, 1u);
  EXPECT_GE(raw->reconnect_calls.load(), 2);  // retried until back
  EXPECT_GT(c.gap_frames, 20u);               // 0.4 s at 200 fps, about 80
  std::lock_guard<std::mutex> lock(m);
  int lost_lines = 0, back_lines = 0, skip_lines = 0;
  for (const auto& l : log) {
    lost_lines += l.find("camera 3: camera lost: link down") != std::string::npos;
    back_lines += l.find("camera back after") != std::string::npos;
    skip_lines += l.find("buffer 7 incomplete") != std::string::npos;
  }
  EXPECT_EQ(lost_lines, 1);  // once, not once per retry
  EXPECT_EQ(back_lines, 1);
  EXPECT_EQ(skip_lines, 1);
}

TEST(FileCameraSource, RealtimeKeepsTheFramesSpacingAndUnpacedDoesNotWait) {
  // A source of 5 frames 50 ms apart.
  class Five : public FrameSource {
   public:
    bool next(Frame& f) override {
      if (n_ == 5) return false;
      f = numbered(n_);
      f.t_capture = 1000 + 0.05 * n_++;
      return true;
    }
    std::string describe() const override { return "five"; }
    uint32_t n_ = 0;
  };
  for (bool realtime : {true, false}) {
    FileCameraSource src(std::make_unique<Five>(), realtime);
    Frame f;
    std::string why;
    std::vector<double> arrivals, captures;
    const auto t0 = std::chrono::steady_clock::now();
    while (src.grab(f, 1.0, why) == GrabStatus::Frame) {
      arrivals.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      captures.push_back(f.t_capture);
    }
    ASSERT_EQ(captures.size(), 5u);
    for (size_t i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(captures[i], 1000 + 0.05 * i);  // stamps kept exactly
    if (realtime) EXPECT_GE(arrivals[4] - arrivals[0], 0.2 - 0.005);  // paced: 4 gaps of 50 ms
    else EXPECT_LT(arrivals[4] - arrivals[0], 0.2);
  }
}

CameraStatus statusWith(double yellow, double blue, SourceState state = SourceState::Running) {
  CameraStatus s;
  s.counters.state = state;
  s.counters.frames_in = s.counters.processed = 100;
  s.fps_in = s.fps_out = 60;
  s.yellow_per_frame = yellow;
  s.blue_per_frame = blue;
  s.robots_per_frame = yellow + blue;
  return s;
}

TEST(HealthMonitor, AVanishedTeamIsDegradedOnceWithTheEvidence) {
  HealthMonitor h;
  int changes = 0;
  for (int i = 0; i < 30; ++i) {
    CameraStatus s = statusWith(5, 6);
    changes += h.update(s);
    EXPECT_EQ(s.health, Health::Ok);
  }
  EXPECT_EQ(changes, 0);
  CameraStatus s;
  for (int i = 0; i < 8; ++i) {
    s = statusWith(0, 6);
    changes += h.update(s);
  }
  EXPECT_EQ(s.health, Health::Degraded);
  EXPECT_NE(s.health_reason.find("no yellow robot"), std::string::npos) << s.health_reason;
  EXPECT_NE(s.health_reason.find("(there were 4.5 per frame)"), std::string::npos) << s.health_reason;  // 25 s of 5, 3 of 0
  EXPECT_EQ(changes, 1);  // logged once, not every second
}

TEST(HealthMonitor, ALostCameraAndProcessingBehindAreNamed) {
  HealthMonitor h;
  CameraStatus s = statusWith(5, 5, SourceState::Lost);
  s.counters.last_problem = "link down";
  EXPECT_TRUE(h.update(s));
  EXPECT_EQ(s.health, Health::Lost);
  EXPECT_NE(s.health_reason.find("link down"), std::string::npos);
  s = statusWith(5, 5);
  s.counters.frames_in = 160;  // 60 more frames, 40 of them dropped
  s.counters.dropped = 40;
  EXPECT_TRUE(h.update(s));
  EXPECT_EQ(s.health, Health::Degraded);
  EXPECT_NE(s.health_reason.find("40 of 60 frames dropped"), std::string::npos) << s.health_reason;
  // One frame in flight on a slow camera (3 in, 2 out, none dropped) is no backlog.
  s = statusWith(5, 5);
  s.counters.frames_in = 163;
  s.counters.dropped = 40;
  s.fps_in = 3;
  s.fps_out = 2;
  h.update(s);
  EXPECT_EQ(s.health, Health::Ok) << s.health_reason;
}

TEST(HealthMonitor, AFieldWithOneTeamOnlyIsHealthy) {
  // A camera over one half may see only one team all along: judged against itself.
  HealthMonitor h;
  for (int i = 0; i < 40; ++i) {
    CameraStatus s = statusWith(0, 6);
    h.update(s);
    EXPECT_EQ(s.health, Health::Ok) << s.health_reason;
  }
}

}  // namespace
}  // namespace dv

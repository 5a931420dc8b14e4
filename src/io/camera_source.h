#pragma once
// A source of frames that may be live: a camera (GenICam through Aravis,
// V4L2 or a network stream through OpenCV), or a file source paced like
// one. Unlike FrameSource it can time out, lose its camera and get it back,
// and be told camera settings. Faults are results, never exceptions, so a
// capture thread never dies of one bad buffer or one unplugged cable.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/frame_source.h"

namespace dv {

enum class GrabStatus {
  Frame,    // `f` holds a new frame
  Timeout,  // nothing within the timeout (not an error by itself)
  Skipped,  // an incomplete or corrupt buffer was dropped; `why` says what
  Lost,     // the camera is gone (`why`); call reconnect() until it is back
  End,      // a finite source (file, video) has no more frames
};

// One GenICam-style setting, "Name=Value", applied in the order given.
struct CameraSetting {
  std::string name;
  std::string value;
};

// "ExposureTime=4000" -> {ExposureTime, 4000}. Throws InputError naming
// `origin` ("--camera-set", "site.yaml:12") for an item without a name or '='.
CameraSetting parseCameraSetting(const std::string& item, const std::string& origin);

// Counters a source keeps about itself (read by the capture thread's owner).
struct SourceCounters {
  uint64_t frames = 0;        // frames handed out
  uint64_t skipped = 0;       // incomplete or corrupt buffers dropped
  uint64_t lost_frames = 0;   // frames the camera numbered but never delivered
};

class CameraSource {
 public:
  virtual ~CameraSource() = default;

  // Waits at most timeout_s for the next frame and fills `f` (its buffer is
  // reused). A live source sets t_capture (Unix s, end of exposure),
  // t_capture_camera (where the camera has a clock) and t_arrival.
  // Must not throw and must not allocate per frame once warmed up.
  virtual GrabStatus grab(Frame& f, double timeout_s, std::string& why) = 0;

  // After Lost: one attempt to open the camera again with the settings last
  // applied. false (and why) while it is still gone.
  virtual bool reconnect(std::string& why) { why = "this source cannot reconnect"; return false; }

  // Applies settings in order; returns one line per setting with the value
  // read back ("ExposureTime = 4000 (us)"). Throws InputError naming the
  // feature and the camera for an unknown feature or a refused value.
  virtual std::vector<std::string> applySettings(const std::vector<CameraSetting>& settings);

  // Unblocks a grab() waiting in another thread (it returns Timeout); used
  // when stopping. Safe to call from any thread.
  virtual void interrupt() {}

  // "genicam://Aravis-Fake-GV01 (BayerRG8 2448x2048)", "video x.mp4", ...
  virtual std::string describe() const = 0;
  // True for a camera (frames come at its pace, latest wins); false for a
  // file source, which yields every frame unless paced.
  virtual bool live() const = 0;
  // Total frames, when known (files); -1 otherwise.
  virtual long expectedCount() const { return -1; }
  virtual SourceCounters counters() const { return {}; }
};

// A FrameSource (images, a directory, a video) as a CameraSource. With
// `realtime` it sleeps so that frames come at their own spacing (t_capture
// differences) from the moment of the first grab, as a camera would
// deliver them. Skip records become Skipped results.
class FileCameraSource : public CameraSource {
 public:
  FileCameraSource(std::unique_ptr<FrameSource> source, bool realtime);
  GrabStatus grab(Frame& f, double timeout_s, std::string& why) override;
  void interrupt() override;
  std::string describe() const override { return source_->describe(); }
  bool live() const override { return realtime_; }
  long expectedCount() const override { return source_->expectedCount(); }
  SourceCounters counters() const override { return counters_; }
  const FrameSource& frames() const { return *source_; }

 private:
  std::unique_ptr<FrameSource> source_;
  bool realtime_;
  size_t skips_seen_ = 0;
  bool started_ = false;
  double first_t_ = 0;        // t_capture of the first frame
  double start_wall_ = 0;     // steady seconds at the first grab
  bool have_pending_ = false; // a frame read but not yet due
  Frame pending_;
  std::atomic<bool> interrupted_{false};
  SourceCounters counters_;
};

}  // namespace dv

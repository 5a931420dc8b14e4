#pragma once
// Cameras OpenCV can read: V4L2 devices (`v4l2:///dev/video0`, `/dev/videoN`:
// webcams for exhibitions) and network streams (`rtsp://`, `http(s)://`
// MJPEG, through FFmpeg). cv::VideoCapture::read blocks, so a small reader
// thread of the source's own reads continuously and keeps only the newest
// frame; grab() waits for it with a timeout and can be interrupted. Three
// image buffers rotate between the reader, the newest slot and the caller's
// Frame, so nothing is allocated per frame once the sizes are known.
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <opencv2/videoio.hpp>
#include <string>
#include <thread>
#include <vector>

#include "io/camera_source.h"

namespace dv {

// True for the specs StreamSource opens (v4l2://, /dev/video, rtsp://, http(s)://).
bool isStreamSpec(const std::string& spec);

class StreamSource : public CameraSource {
 public:
  // Opens the device or URL. Throws InputError naming `spec`: no such
  // device (with the V4L2 devices present), a stream that does not answer.
  explicit StreamSource(const std::string& spec);
  ~StreamSource() override;

  // Frame: Bgr8; t_arrival = host Unix time when read; t_capture = the V4L2
  // buffer time stamp mapped to Unix time where it is plausible (never later
  // than t_arrival), else t_arrival; t_capture_camera = the backend's time
  // stamp in s (V4L2: monotonic clock, streams: stream time), else -1.
  // Lost (why) when the stream ends, errors or stalls for kStallTimeout_s.
  GrabStatus grab(Frame& f, double timeout_s, std::string& why) override;
  // Opens the device or URL again and re-applies the settings last applied.
  bool reconnect(std::string& why) override;
  // Width, Height, AcquisitionFrameRate (fps), ExposureTime (us),
  // ExposureAuto / GainAuto / BalanceWhiteAuto (Off, Continuous), Gain
  // (device units), BalanceWhiteTemperature (K); each read back. Unknown
  // names and refused values throw InputError (see streamSettingNames()).
  std::vector<std::string> applySettings(const std::vector<CameraSetting>& settings) override;
  void interrupt() override;
  std::string describe() const override;
  bool live() const override { return true; }
  // lost_frames: frames read but replaced by a newer one before grab() took them.
  SourceCounters counters() const override;

  static constexpr double kStallTimeout_s = 3.0;

 private:
  bool open(std::string& why);
  void updateDescription();  // "<spec> (WxH, fps)" from the open capture
  void startReader();
  void stopReader();
  void readLoop();
  std::string applyOne(const CameraSetting& s);

  std::string spec_;
  std::string device_;                   // /dev/videoN, or empty for a network stream
  std::string url_;                      // what VideoCapture opens
  cv::VideoCapture capture_;             // used by the reader thread while it runs
  std::vector<CameraSetting> settings_;  // applied, in order, for reconnect()

  std::thread reader_;
  bool reader_running_ = false;  // owner thread only

  mutable std::mutex mutex_;  // guards everything below
  std::string description_;
  std::condition_variable changed_;
  bool stop_ = false;         // reader: finish
  bool reader_done_ = false;  // reader: ended (reason in lost_reason_)
  bool lost_ = false;         // reported as Lost until reconnect()
  bool interrupted_ = false;
  std::string lost_reason_;
  cv::Mat newest_;  // newest frame not yet taken
  bool fresh_ = false;
  double newest_t_capture_ = 0, newest_t_camera_ = -1, newest_t_arrival_ = 0;
  uint32_t newest_index_ = 0;
  double last_frame_steady_ = 0;  // steady s of the newest frame (or reader start)
  double last_t_capture_ = 0;     // keeps t_capture strictly increasing
  SourceCounters counters_;
};

}  // namespace dv

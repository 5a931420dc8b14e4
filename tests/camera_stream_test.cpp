// Network streams and V4L2 devices through StreamSource, with real
// components: an HTTP MJPEG stream served on loopback by ffmpeg, started by
// the test as a child process, and whatever V4L2 device the machine has
// (none in CI, where the v4l2loopback module cannot be loaded: those tests
// skip and say so).
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "camera/open_camera.h"
#include "camera/stream_source.h"
#include "camera/v4l2_list.h"
#include "core/error.h"

namespace dv {
namespace {

bool ffmpegOnPath() { return std::system("command -v ffmpeg > /dev/null 2>&1") == 0; }

#define REQUIRE_FFMPEG() \
  if (!ffmpegOnPath())   \
  GTEST_SKIP() << "ffmpeg is not on PATH (scripts/setup.sh installs it); no stream to test with"

// A TCP port on 127.0.0.1 that nobody listens on right now.
uint16_t freePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof addr;
  ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  ::close(fd);
  return ntohs(addr.sin_port);
}

double unixNow() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// ffmpeg's test pattern as an HTTP multipart-JPEG stream for one client,
// paced at its frame rate (-re), as a network camera would send it.
class MjpegServer {
 public:
  explicit MjpegServer(uint16_t port) : port_(port) { start(); }
  ~MjpegServer() { stop(); }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/stream.mjpg"; }

  void start() {
    const std::string out = url();
    pid_ = ::fork();
    if (pid_ == 0) {
      ::execlp("ffmpeg", "ffmpeg", "-nostdin", "-loglevel", "quiet", "-re", "-f", "lavfi", "-i",
               "testsrc=size=320x240:rate=30", "-f", "mpjpeg", "-q:v", "5", "-listen", "1", out.c_str(),
               static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  // Freezes the server with its connection open: a camera that hangs.
  void freeze() { ::kill(pid_, SIGSTOP); }
  void stop() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  uint16_t port_;
  pid_t pid_ = -1;
};

// ffmpeg needs a moment to listen: try to open until it answers (10 s limit).
std::unique_ptr<StreamSource> openWhenUp(const std::string& url) {
  std::string last;
  for (int attempt = 0; attempt < 100; ++attempt) {
    try {
      return std::make_unique<StreamSource>(url);
    } catch (const InputError& e) {
      last = e.what();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ADD_FAILURE() << "the ffmpeg stream never answered: " << last;
  return nullptr;
}

// Grabs until a frame comes (safety limit 10 s); returns the last status.
GrabStatus grabFrame(CameraSource& source, Frame& f, std::string& why) {
  GrabStatus s = GrabStatus::Timeout;
  for (int i = 0; i < 20 && s == GrabStatus::Timeout; ++i) s = source.grab(f, 0.5, why);
  return s;
}

TEST(CameraStream, HttpMjpegFramesArriveWithLiveTimeStamps) {
  REQUIRE_FFMPEG();
  MjpegServer server(freePort());
  auto source = openWhenUp(server.url());
  ASSERT_TRUE(source);
  EXPECT_TRUE(source->live());
  EXPECT_NE(source->describe().find("320x240"), std::string::npos) << source->describe();

  Frame f;
  std::string why;
  double previous_capture = 0;
  int64_t previous_index = -1;
  std::set<const uchar*> buffers;  // pixel buffers handed out after warm-up
  for (int i = 0; i < 30; ++i) {
    ASSERT_EQ(grabFrame(*source, f, why), GrabStatus::Frame) << "frame " << i << ": " << why;
    EXPECT_EQ(f.image.cols, 320);
    EXPECT_EQ(f.image.rows, 240);
    EXPECT_EQ(f.image.type(), CV_8UC3);
    EXPECT_EQ(f.format, PixelFormat::Bgr8);
    EXPECT_GT(f.t_capture, previous_capture) << "frame " << i;
    EXPECT_LE(f.t_capture, f.t_arrival);
    EXPECT_LE(f.t_arrival - f.t_capture, 0.005);
    EXPECT_LT(std::abs(f.t_arrival - unixNow()), 5.0) << "t_arrival is not Unix time";
    EXPECT_GT(int64_t(f.index), previous_index);
    EXPECT_EQ(f.name.rfind(server.url() + "#", 0), 0u) << f.name;
    previous_capture = f.t_capture;
    previous_index = f.index;
    if (i >= 5) buffers.insert(f.image.data);
  }
  // The reader's, the newest slot's and the caller's buffers rotate: no
  // frame gets a freshly allocated one.
  EXPECT_LE(buffers.size(), 3u);
  // testsrc is a colour test card, not a black or grey frame.
  const cv::Scalar mean = cv::mean(f.image);
  EXPECT_GT(mean[0] + mean[1] + mean[2], 100.0);
  EXPECT_NE(mean[0], mean[2]);
  const SourceCounters c = source->counters();
  EXPECT_EQ(c.frames, 30u);
  EXPECT_EQ(c.skipped, 0u);
}

TEST(CameraStream, ServerGoneIsLostAndReconnectWaitsForItsReturn) {
  REQUIRE_FFMPEG();
  MjpegServer server(freePort());
  auto source = openWhenUp(server.url());
  ASSERT_TRUE(source);
  Frame f;
  std::string why;
  ASSERT_EQ(grabFrame(*source, f, why), GrabStatus::Frame) << why;

  server.stop();
  GrabStatus s = GrabStatus::Frame;
  for (int i = 0; i < 40 && s != GrabStatus::Lost; ++i) s = source->grab(f, 0.25, why);  // 10 s safety limit
  ASSERT_EQ(s, GrabStatus::Lost) << "the stream's end was not noticed";
  EXPECT_FALSE(why.empty());
  EXPECT_EQ(source->grab(f, 0.1, why), GrabStatus::Lost) << "Lost until reconnect()";

  std::string reconnect_why;
  EXPECT_FALSE(source->reconnect(reconnect_why)) << "reconnected to a server that is gone";
  EXPECT_NE(reconnect_why, "");

  server.start();
  bool back = false;
  for (int i = 0; i < 100 && !back; ++i) {  // 10 s safety limit while ffmpeg starts
    back = source->reconnect(reconnect_why);
    if (!back) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_TRUE(back) << reconnect_why;
  double previous = 0;
  for (int i = 0; i < 5; ++i) {
    ASSERT_EQ(grabFrame(*source, f, why), GrabStatus::Frame) << why;
    EXPECT_EQ(f.image.cols, 320);
    EXPECT_GT(f.t_capture, previous);
    previous = f.t_capture;
  }
}

TEST(CameraStream, StreamThatHangsIsLost) {
  REQUIRE_FFMPEG();
  MjpegServer server(freePort());
  auto source = openWhenUp(server.url());
  ASSERT_TRUE(source);
  Frame f;
  std::string why;
  ASSERT_EQ(grabFrame(*source, f, why), GrabStatus::Frame) << why;
  server.freeze();
  GrabStatus s = GrabStatus::Frame;
  for (int i = 0; i < 60 && s != GrabStatus::Lost; ++i) s = source->grab(f, 0.25, why);  // 15 s safety limit
  EXPECT_EQ(s, GrabStatus::Lost) << "a stream that sends nothing more was not noticed";
  EXPECT_FALSE(why.empty());
  source.reset();  // must not wait for the frozen server for ever
}

TEST(CameraStream, SettingsThatDoNotMapAreClearErrors) {
  REQUIRE_FFMPEG();
  MjpegServer server(freePort());
  auto source = openWhenUp(server.url());
  ASSERT_TRUE(source);
  try {
    source->applySettings({{"BalanceRatio", "1.3"}});
    FAIL() << "BalanceRatio accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("BalanceRatio"), std::string::npos) << m;
    EXPECT_NE(m.find(server.url()), std::string::npos) << m;
    EXPECT_NE(m.find("ExposureTime"), std::string::npos) << "should list the names that map: " << m;
    EXPECT_NE(m.find("BalanceWhiteTemperature"), std::string::npos) << m;
  }
  // A name that maps, but a network stream cannot be set from here.
  try {
    source->applySettings({{"Width", "640"}});
    FAIL() << "Width accepted by a network stream";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Width=640"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("refused"), std::string::npos) << e.what();
  }
  EXPECT_THROW(source->applySettings({{"ExposureAuto", "Sometimes"}}), InputError);
  EXPECT_THROW(source->applySettings({{"ExposureTime", "fast"}}), InputError);
  // The source still streams after the refused settings.
  Frame f;
  std::string why;
  EXPECT_EQ(grabFrame(*source, f, why), GrabStatus::Frame) << why;
}

TEST(CameraStream, InterruptEndsAWaitingGrab) {
  REQUIRE_FFMPEG();
  MjpegServer server(freePort());
  auto source = openWhenUp(server.url());
  ASSERT_TRUE(source);
  Frame f;
  std::string why;
  ASSERT_EQ(grabFrame(*source, f, why), GrabStatus::Frame) << why;
  source->interrupt();  // before the grab: the next grab returns at once, frames or not
  EXPECT_EQ(source->grab(f, 60.0, why), GrabStatus::Timeout);
  EXPECT_EQ(grabFrame(*source, f, why), GrabStatus::Frame)
      << "an interrupt must not stop the stream: " << why;
}

TEST(CameraStream, FactoryOpensStreamsAndNamesAStreamThatIsNotThere) {
  const std::string url = "http://127.0.0.1:" + std::to_string(freePort()) + "/nothing.mjpg";
  EXPECT_TRUE(isStreamSpec(url));
  EXPECT_TRUE(isStreamSpec("rtsp://10.0.0.5/stream"));
  EXPECT_TRUE(isStreamSpec("v4l2:///dev/video0"));
  EXPECT_FALSE(isStreamSpec("genicam://"));
  try {
    openCameraSource(url, CameraSourceOptions{});
    FAIL() << "a stream nobody serves was opened";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), url);
  }
}

TEST(CameraV4l2, MissingDeviceIsNamedWithTheDevicesPresent) {
  try {
    StreamSource source("v4l2:///dev/video987");
    FAIL() << "/dev/video987 opened";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "v4l2:///dev/video987");
    EXPECT_NE(std::string(e.what()).find("V4L2 devices here: "), std::string::npos) << e.what();
  }
  try {
    StreamSource source("v4l2://");
    FAIL() << "an empty device path was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("v4l2:///dev/video0"), std::string::npos) << e.what();
  }
}

TEST(CameraV4l2, ListsOnlyCaptureDevices) {
  EXPECT_FALSE(queryV4l2Device("/dev/null")) << "/dev/null answers no VIDIOC_QUERYCAP";
  EXPECT_FALSE(queryV4l2Device("/dev/video987"));
  for (const V4l2Device& d : listV4l2Devices()) {
    EXPECT_EQ(d.path.rfind("/dev/video", 0), 0u) << d.path;
    EXPECT_FALSE(d.name.empty()) << d.path;
  }
}

// Real where the machine has a camera (or a loaded v4l2loopback device fed
// by a producer); skipped, saying so, where it has none.
TEST(CameraV4l2, DeviceDeliversFrames) {
  std::vector<V4l2Device> devices;
  for (auto& d : listV4l2Devices()) {
    if (!d.formats.empty()) devices.push_back(d);
  }
  if (devices.empty())
    GTEST_SKIP() << "no V4L2 capture device here (no /dev/video* that answers VIDIOC_QUERYCAP with a capture "
                    "format); load v4l2loopback and feed it, or attach a webcam, to run this test";
  const V4l2Device& d = devices.front();
  EXPECT_FALSE(d.formats.empty());
  std::unique_ptr<StreamSource> source;
  try {
    source = std::make_unique<StreamSource>("v4l2://" + d.path);
  } catch (const InputError& e) {
    GTEST_SKIP() << d.path << " (" << d.name << ") cannot be opened here: " << e.what();
  }
  Frame f;
  std::string why;
  double previous = 0;
  for (int i = 0; i < 10; ++i) {
    const GrabStatus s = grabFrame(*source, f, why);
    if (i == 0 && s == GrabStatus::Lost)
      GTEST_SKIP() << d.path
                   << " opens but delivers no frames (a loopback device without a producer?): " << why;
    ASSERT_EQ(s, GrabStatus::Frame) << d.path << ": " << why;
    EXPECT_GT(f.image.cols, 0);
    EXPECT_EQ(f.image.type(), CV_8UC3);
    EXPECT_GT(f.t_capture, previous);
    EXPECT_LE(f.t_capture, f.t_arrival);
    EXPECT_LE(f.t_arrival - f.t_capture, 0.1) << "a V4L2 time stamp maps to the last 100 ms";
    previous = f.t_capture;
  }
  // Settings read back: the current width, set again, must be accepted as is.
  const std::vector<std::string> lines = source->applySettings(
      {{"Width", std::to_string(f.image.cols)}, {"Height", std::to_string(f.image.rows)}});
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "Width = " + std::to_string(f.image.cols) + " (px)");
  EXPECT_THROW(source->applySettings({{"BalanceRatio", "1"}}), InputError);
  EXPECT_EQ(grabFrame(*source, f, why), GrabStatus::Frame) << why;

  // Reopened, with the settings applied again.
  const int cols = f.image.cols;
  ASSERT_TRUE(source->reconnect(why)) << why;
  ASSERT_EQ(grabFrame(*source, f, why), GrabStatus::Frame) << why;
  EXPECT_EQ(f.image.cols, cols);
}

}  // namespace
}  // namespace dv

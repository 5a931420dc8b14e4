// Where detections go when things fail mid-run: the disk fills (the SSL log
// stops with one warning naming the file, every later detection still goes
// out) or the network interface goes away and comes back (publishing says
// so once and resumes by itself).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <net/if.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/packet_outputs.h"
#include "geometry/geometry_io.h"
#include "net/multicast.h"
#include "temp_dir.h"

namespace dv::app {
namespace {

// About 30 KB serialized: a few of them overflow the log's 128 KiB buffer,
// so the write fails inside the run, not only at the close.
ssl::SSL_WrapperPacket bigPacket(uint32_t frame) {
  ssl::SSL_WrapperPacket p;
  auto* d = p.mutable_detection();
  d->set_frame_number(frame);
  d->set_t_capture(1.0);
  d->set_t_sent(1.0);
  d->set_camera_id(0);
  for (int i = 0; i < 1000; ++i) {
    auto* r = d->add_robots_yellow();
    r->set_confidence(1);
    r->set_x(float(i));
    r->set_y(float(-i));
    r->set_pixel_x(float(i));
    r->set_pixel_y(float(i));
  }
  return p;
}

TEST(PacketOutputs, FullDiskStopsTheLogOnceAndDetectionsGoOn) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  TempDir dir("dv_outputs_full");
  OutputOptions o;
  o.publish = false;
  o.ssl_log = "/dev/full";
  o.jsonl = dir.file("det.jsonl");
  o.who = "test";
  PacketOutputs outputs(o, toProto(loadGeometry(std::string(DV_SOURCE_DIR) + "/config/fields/division_b.json")));
  ::testing::internal::CaptureStderr();
  for (uint32_t i = 0; i < 20; ++i) ASSERT_NO_THROW(outputs.detection(bigPacket(i)));
  const std::string during = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(outputs.recordingFailure().find("/dev/full"), std::string::npos) << outputs.recordingFailure();
  EXPECT_NE(during.find("test: warning: recording stopped: /dev/full"), std::string::npos) << during;
  EXPECT_NE(during.find("No space left on device"), std::string::npos) << during;
  EXPECT_EQ(during.find("recording stopped", during.find("recording stopped") + 20), std::string::npos) << during;
  ASSERT_NO_THROW(outputs.finish());
  EXPECT_NE(outputs.describe().find("recording stopped: /dev/full"), std::string::npos) << outputs.describe();
  std::ifstream in(dir.file("det.jsonl"));
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, 20);
}

bool setLoopbackUp(bool up) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, "lo", IFNAMSIZ - 1);
  bool ok = fd >= 0 && ::ioctl(fd, SIOCGIFFLAGS, &ifr) == 0;
  if (ok) {
    ifr.ifr_flags = short(up ? ifr.ifr_flags | IFF_UP : ifr.ifr_flags & ~IFF_UP);
    ok = ::ioctl(fd, SIOCSIFFLAGS, &ifr) == 0;
  }
  if (fd >= 0) ::close(fd);
  return ok;
}

// In a network namespace of its own (lo only, starting down), so that taking
// the interface away touches nothing else on the machine. Exit codes name
// the step that went wrong; 77: no namespace to be had here.
int publishWhileTheInterfaceGoesAndComes(const std::string& stderr_file) {
  const int unshared = ::geteuid() == 0 ? ::unshare(CLONE_NEWNET) : ::unshare(CLONE_NEWUSER | CLONE_NEWNET);
  if (unshared != 0 || !setLoopbackUp(true)) return 77;
  const int err = ::open(stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (err < 0 || ::dup2(err, 2) < 0) return 10;
  try {
    const uint16_t port = 10006;
    MulticastReceiver rx("224.5.23.2", port, "127.0.0.1");
    OutputOptions o;
    o.port = port;
    o.interface_addr = "127.0.0.1";
    o.publish_geometry = false;
    o.who = "test";
    PacketOutputs outputs(o, toProto(loadGeometry(std::string(DV_SOURCE_DIR) + "/config/fields/division_b.json")));
    std::string payload;
    outputs.detection(bigPacket(0));
    if (!rx.receive(2.0, payload)) return 11;
    if (!setLoopbackUp(false)) return 12;
    for (uint32_t i = 1; i <= 3; ++i) outputs.detection(bigPacket(i));
    if (!setLoopbackUp(true)) return 13;
    outputs.detection(bigPacket(4));
    if (!rx.receive(2.0, payload)) return 14;
    ssl::SSL_WrapperPacket got;
    if (!got.ParseFromString(payload) || got.detection().frame_number() != 4) return 15;
    if (outputs.sendFailures() != 3) return 16;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exception: %s\n", e.what());
    return 17;
  }
  std::fflush(stderr);
  return 0;
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(PacketOutputs, InterfaceGoneAndBackIsSaidOnceAndPublishingResumes) {
  TempDir dir("dv_outputs_iface");
  const std::string log = dir.file("stderr.txt");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) ::_exit(publishWhileTheInterfaceGoesAndComes(log));
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << WTERMSIG(status);
  if (WEXITSTATUS(status) == 77) GTEST_SKIP() << "no network namespace can be made here (unshare refused)";
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  ASSERT_EQ(WEXITSTATUS(status), 0) << "step " << WEXITSTATUS(status) << " failed; stderr:\n" << text.str();
  EXPECT_EQ(count(text.str(), "test: warning: cannot publish on udp 224.5.23.2:10006: Network is unreachable"), 1u)
      << text.str();
  EXPECT_EQ(count(text.str(), "publishing on udp 224.5.23.2:10006 again after 3 frame(s) not sent"), 1u)
      << text.str();
}

}  // namespace
}  // namespace dv::app

// A processor started without --geometry takes the field and its own
// calibration from the geometry publisher on the vision group (real UDP
// multicast on loopback), and says clearly when none arrives.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include "geometry/geometry_io.h"
#include "net/geometry_publisher.h"
#include "synth/renderer.h"
#include "synth/scene.h"
#include "temp_dir.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int runCli(const std::string& args, const fs::path& dir, std::string& out) {
  const fs::path o = dir / "out.txt";
  const std::string cmd = std::string("'") + DV_CLI_PATH + "' " + args + " >'" + o.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  out = readAll(o);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

uint16_t randomPort() {
  std::random_device rd;
  return static_cast<uint16_t>(49000 + rd() % 8000);
}

TEST(CliNetworkGeometry, RunTakesItsCalibrationFromThePublisher) {
  const TempDir tmp("dv_net_geometry");
  const fs::path& dir = tmp.path();
  SceneSpec spec = defaultScene();
  spec.frames = 1;
  writeScene(spec, dir.string());

  GeometryPublisherOptions po;
  po.listen_addr = "127.0.0.1";
  po.listen_port = 0;
  po.interval_s = 0.1;
  po.port = randomPort();
  po.interface_addr = "127.0.0.1";
  GeometryPublisher publisher(Renderer(spec).geometry(), po);
  std::thread thread([&] { publisher.run(20.0); });

  std::string out;
  const std::string common = " --multicast-port " + std::to_string(po.port) +
                             " --multicast-interface 127.0.0.1 --jsonl " + (dir / "det.jsonl").string();
  const int code = runCli("run --source " + dir.string() + " --camera-id 0" + common, dir, out);
  // A camera the publisher does not know: a clear message naming the source.
  std::string missing;
  const int missing_code =
      runCli("run --source " + dir.string() + " --camera-id 5 --geometry-timeout 0.5" + common, dir, missing);
  publisher.stop();
  thread.join();

  EXPECT_EQ(code, 0) << out;
  EXPECT_NE(out.find("1 processed, 0 skipped"), std::string::npos) << out;
  EXPECT_FALSE(readAll(dir / "det.jsonl").empty());
  EXPECT_EQ(missing_code, 2) << missing;
  EXPECT_NE(missing.find("no geometry with a calibration for camera 5"), std::string::npos) << missing;
  EXPECT_NE(missing.find("udp 224.5.23.2:" + std::to_string(po.port)), std::string::npos) << missing;
}

}  // namespace
}  // namespace dv

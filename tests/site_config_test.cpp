// The site config of `dotvision serve`: the shipped files parse to what they
// say, and every kind of bad input is one error naming file, line and key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/site_config.h"
#include "app/synthetic_camera.h"
#include "core/error.h"
#include "synth/scene.h"
#include "temp_dir.h"

namespace dv::app {
namespace {

const std::string kConfigDir = std::string(DV_SOURCE_DIR) + "/config/";

// Parses `yaml` (named "site.yaml") expecting an error at `line` about `key`
// whose text contains `fragment`; returns the message for further checks.
std::string expectError(const std::string& yaml, int line, const std::string& key, const std::string& fragment) {
  try {
    parseSiteConfig(yaml, "site.yaml");
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.source(), "site.yaml:" + std::to_string(line)) << what;
    if (!key.empty()) {
      EXPECT_NE(what.find("key '" + key + "': "), std::string::npos) << what;
    }
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
    return what;
  }
  ADD_FAILURE() << "no error for:\n" << yaml;
  return "";
}

// A valid file with one camera, to which a test appends one section.
const std::string kOneCamera = "cameras:\n  - {id: 0, source: synthetic://two_cameras_overlap/0}\n";  // lines 1-2

TEST(SiteConfigFiles, ExampleParsesToTheDocumentedDefaults) {
  const SiteConfig c = loadSiteConfig(kConfigDir + "site.example.yaml");
  EXPECT_EQ(c.path, kConfigDir + "site.example.yaml");
  ASSERT_EQ(c.cameras.size(), 2u);
  EXPECT_EQ(c.cameras[0].id, 0u);
  EXPECT_EQ(c.cameras[0].source, "synthetic://two_cameras_overlap/0");
  EXPECT_EQ(c.cameras[1].id, 1u);
  EXPECT_EQ(c.cameras[1].source, "synthetic://two_cameras_overlap/1");
  EXPECT_GT(c.cameras[1].line, c.cameras[0].line);
  // The example says that the values it writes are the defaults: camera 0
  // spells every key out, camera 1 none, and both equal the struct's defaults.
  const SiteCamera d;
  for (const SiteCamera& cam : c.cameras) {
    EXPECT_TRUE(cam.settings.empty());
    EXPECT_EQ(cam.bayer, d.bayer);
    EXPECT_EQ(cam.bayer_sampling, d.bayer_sampling);
    EXPECT_EQ(cam.full_search, d.full_search);
    EXPECT_EQ(cam.backend, d.backend);
    EXPECT_EQ(cam.threads, d.threads);
    EXPECT_EQ(cam.fps, d.fps);
    EXPECT_EQ(cam.realtime, d.realtime);
    EXPECT_EQ(cam.loop, d.loop);
  }
  const SiteNetwork n;
  EXPECT_EQ(c.network.vision_group, "224.5.23.2");
  EXPECT_EQ(c.network.vision_group, n.vision_group);
  EXPECT_EQ(c.network.vision_port, 10006);
  EXPECT_EQ(c.network.interface_addr, "");
  EXPECT_EQ(c.network.geometry, "auto");
  EXPECT_EQ(c.network.geometry_file, "");
  EXPECT_EQ(c.network.geometry_timeout, n.geometry_timeout);
  EXPECT_TRUE(c.network.referee);
  EXPECT_EQ(c.network.referee_group, "224.5.23.1");
  EXPECT_EQ(c.network.referee_port, 10003);
  EXPECT_EQ(c.robot_heights.default_mm, SiteRobotHeights().default_mm);
  EXPECT_FALSE(c.robot_heights.yellow_mm.has_value());
  EXPECT_FALSE(c.robot_heights.blue_mm.has_value());
  const std::map<std::string, double> teams = {{"tigers mannheim", 145}, {"er-force", 150}};
  EXPECT_EQ(c.robot_heights.teams, teams);
  const SiteDetector det;
  EXPECT_EQ(c.detector.guessed_ids, det.guessed_ids);
  EXPECT_EQ(c.detector.tracking, det.tracking);
  EXPECT_EQ(c.detector.ball_radius, det.ball_radius);
  const SiteRecord r;
  EXPECT_EQ(c.record.raw_dir, r.raw_dir);
  EXPECT_EQ(c.record.raw_seconds, r.raw_seconds);
  EXPECT_EQ(c.record.on_health_change, r.on_health_change);
  EXPECT_EQ(c.record.ssl_log, r.ssl_log);
  EXPECT_EQ(c.console.http, SiteConsole().http);
  EXPECT_EQ(c.console.http, "127.0.0.1:8080");  // loopback only unless told
  EXPECT_EQ(c.console.token_file, SiteConsole().token_file);
  EXPECT_EQ(c.status_interval, SiteConfig().status_interval);
}

// "synthetic://SCENE/ID" -> the preset's camera with that id, checked to exist.
const CameraCalibration& presetCamera(const std::string& source, SceneSpec& scene) {
  const std::string prefix = "synthetic://";
  EXPECT_EQ(source.rfind(prefix, 0), 0u) << source;
  const size_t slash = source.rfind('/');
  scene = presetScene(source.substr(prefix.size(), slash - prefix.size()));
  const uint32_t id = uint32_t(std::stoul(source.substr(slash + 1)));
  for (const SceneCamera& cam : scene.cameras)
    if (cam.calib.camera_id == id) return cam.calib;
  throw std::runtime_error(source + ": the scene has no camera " + std::to_string(id));
}

TEST(SiteConfigFiles, ShippedSitesNameCamerasOfBuiltInScenes) {
  struct Site {
    std::string file;
    size_t cameras;
    uint32_t width, height;
    double field_length;
  };
  for (const Site& site : {Site{"site.example.yaml", 2, 2448, 2048, 9000},
                           Site{"site.division_a.yaml", 4, 1224, 1024, 12000},
                           Site{"site.two_2448.yaml", 2, 2448, 2048, 9000}}) {
    SCOPED_TRACE(site.file);
    const SiteConfig c = loadSiteConfig(kConfigDir + site.file);
    ASSERT_EQ(c.cameras.size(), site.cameras);
    for (size_t i = 0; i < c.cameras.size(); ++i) {
      EXPECT_EQ(c.cameras[i].id, i);
      SceneSpec scene;
      const CameraCalibration& calib = presetCamera(c.cameras[i].source, scene);
      EXPECT_EQ(calib.camera_id, c.cameras[i].id);
      EXPECT_EQ(calib.image_width, site.width);
      EXPECT_EQ(calib.image_height, site.height);
      EXPECT_EQ(scene.field.field_length, site.field_length);
    }
    EXPECT_EQ(c.network.geometry, "auto");
  }
  EXPECT_EQ(loadSiteConfig(kConfigDir + "site.two_2448.yaml").cameras[1].backend, "cpu");
}

TEST(SiteConfigParse, SettingsKeepTheirOrder) {
  const SiteConfig c = parseSiteConfig(R"(cameras:
  - id: 3
    source: genicam://Basler-1234
    settings:
      - BalanceRatioSelector=Red
      - BalanceRatio=1.6
      - BalanceRatioSelector=Blue
      - BalanceRatio = 2.1
      - ExposureTime=4000
)",
                                       "site.yaml");
  ASSERT_EQ(c.cameras.size(), 1u);
  const auto& s = c.cameras[0].settings;
  ASSERT_EQ(s.size(), 5u);
  const std::vector<std::pair<std::string, std::string>> expected = {{"BalanceRatioSelector", "Red"},
                                                                    {"BalanceRatio", "1.6"},
                                                                    {"BalanceRatioSelector", "Blue"},
                                                                    {"BalanceRatio", "2.1"},
                                                                    {"ExposureTime", "4000"}};
  for (size_t i = 0; i < s.size(); ++i) {
    EXPECT_EQ(s[i].name, expected[i].first);
    EXPECT_EQ(s[i].value, expected[i].second);
  }
  EXPECT_EQ(c.cameras[0].line, 2);
}

TEST(SiteConfigParse, ValuesOtherThanTheDefaults) {
  const SiteConfig c = parseSiteConfig(kOneCamera + R"(network:
  vision: {group: 239.1.2.3, port: 10020, interface: 127.0.0.1}
  geometry: {source: publish, file: field.json, timeout: 2.5}
  referee: {enabled: false, port: 10099}
robot_heights: {default: 135, yellow: 150, blue: ~}
detector: {guessed_ids: false, tracking: false, ball_radius: 21}
record: {raw_dir: /tmp/raw, raw_seconds: 120, on_health_change: no, ssl_log: x.log.gz}
status_interval: 0
)",
                                       "site.yaml");
  EXPECT_EQ(c.network.vision_group, "239.1.2.3");
  EXPECT_EQ(c.network.vision_port, 10020);
  EXPECT_EQ(c.network.interface_addr, "127.0.0.1");
  EXPECT_EQ(c.network.geometry, "publish");
  EXPECT_EQ(c.network.geometry_file, "field.json");
  EXPECT_EQ(c.network.geometry_timeout, 2.5);
  EXPECT_FALSE(c.network.referee);
  EXPECT_EQ(c.network.referee_group, "224.5.23.1");  // not given: default
  EXPECT_EQ(c.network.referee_port, 10099);
  EXPECT_EQ(c.robot_heights.default_mm, 135);
  EXPECT_EQ(c.robot_heights.yellow_mm, 150);
  EXPECT_FALSE(c.robot_heights.blue_mm.has_value());
  EXPECT_FALSE(c.detector.guessed_ids);
  EXPECT_FALSE(c.detector.tracking);
  EXPECT_EQ(c.detector.ball_radius, 21);
  EXPECT_EQ(c.record.raw_dir, "/tmp/raw");
  EXPECT_EQ(c.record.raw_seconds, 120);
  EXPECT_FALSE(c.record.on_health_change);
  EXPECT_EQ(c.record.ssl_log, "x.log.gz");
  EXPECT_EQ(c.status_interval, 0);
}

TEST(SiteConfigParse, TeamNamesIgnoreCase) {
  const SiteConfig c = parseSiteConfig(kOneCamera + R"(robot_heights:
  teams: {"TIGERs Mannheim": 145, " ER-Force ": 150, robots-r-us: 130}
)",
                                       "site.yaml");
  const std::map<std::string, double> teams = {{"tigers mannheim", 145}, {"er-force", 150}, {"robots-r-us", 130}};
  EXPECT_EQ(c.robot_heights.teams, teams);
  EXPECT_EQ(c.robot_heights.teams.at(teamKey("tigers MANNHEIM")), 145);
  EXPECT_EQ(c.robot_heights.teams.at(teamKey("ER-FORCE")), 150);
  EXPECT_EQ(c.robot_heights.teams.count(teamKey("Unknown Team")), 0u);

  const std::string what = expectError(kOneCamera + R"(robot_heights:
  teams:
    ER-Force: 150
    TIGERs Mannheim: 145
    er-force: 148
)",
                                       7, "robot_heights.teams[\"er-force\"]", "the same team as 'ER-Force' (line 5)");
  EXPECT_NE(what.find("ignoring case"), std::string::npos) << what;
  expectError(kOneCamera + "robot_heights:\n  teams: {\"\": 140}\n", 4, "robot_heights.teams[\"\"]", "empty");
  expectError(kOneCamera + "robot_heights:\n  teams: [ER-Force]\n", 4, "robot_heights.teams", "expected a map");
  expectError(kOneCamera + "robot_heights:\n  teams:\n    ER-Force:\n", 5, "robot_heights.teams[\"ER-Force\"]",
              "no height");
}

TEST(SiteConfigErrors, UnknownKeysListTheAllowedOnesAndSuggest) {
  std::string what = expectError(kOneCamera + "network:\n  vision:\n    group: 224.5.23.2\n  vison: {port: 1}\n",
                                 6, "network.vison", "unknown key (allowed here: vision, geometry, referee)");
  EXPECT_NE(what.find("did you mean 'vision'?"), std::string::npos) << what;
  what = expectError("cameras:\n  - id: 0\n    sorce: x.png\n", 3, "cameras[0].sorce", "did you mean 'source'?");
  EXPECT_NE(what.find("allowed here: id, source, settings, bayer"), std::string::npos) << what;
  what = expectError(kOneCamera + "colour_classes: 4\n", 3, "colour_classes",
                     "unknown key (allowed at the top: cameras, network, robot_heights, detector, record, "
                     "console, status_interval)");
  EXPECT_EQ(what.find("did you mean"), std::string::npos) << what;
  expectError(kOneCamera + "Detector: {}\n", 3, "Detector", "did you mean 'detector'?");
  expectError(kOneCamera + "record: {raw_second: 3}\n", 3, "record.raw_second", "did you mean 'raw_seconds'?");
}

TEST(SiteConfigErrors, WrongTypes) {
  expectError(kOneCamera + "network:\n  vision: {port: abc}\n", 4, "network.vision.port",
              "expected a whole number, got 'abc'");
  expectError(kOneCamera + "network:\n  vision: {port: 100.5}\n", 4, "network.vision.port",
              "expected a whole number, got '100.5'");
  expectError(kOneCamera + "detector:\n  ball_radius: abc\n", 4, "detector.ball_radius",
              "expected a number, got 'abc'");
  expectError(kOneCamera + "detector:\n  tracking: maybe\n", 4, "detector.tracking",
              "expected true or false, got 'maybe'");
  expectError(kOneCamera + "robot_heights:\n  default: [140]\n", 4, "robot_heights.default",
              "expected a number, got a list");
  expectError(kOneCamera + "network: 5\n", 3, "network", "expected a map of keys");
  expectError(kOneCamera + "record:\n  raw_dir: {a: 1}\n", 4, "record.raw_dir", "expected a text, got a map");
  expectError("cameras:\n  - id: zero\n    source: a.png\n", 2, "cameras[0].id", "expected a whole number, got 'zero'");
  expectError("cameras: {id: 0}\n", 1, "cameras", "expected a list of cameras");
  expectError("cameras:\n  - synthetic://two_cameras_overlap/0\n", 2, "cameras[0]", "expected a camera");
  expectError("- id: 0\n", 1, "", "expected a map of keys");
}

TEST(SiteConfigErrors, OutOfRangeValues) {
  expectError(kOneCamera + "network:\n  vision: {port: 0}\n", 4, "network.vision.port", "must be 1..65535");
  expectError(kOneCamera + "network:\n  referee:\n    port: 70000\n", 5, "network.referee.port", "must be 1..65535");
  std::string what = expectError(kOneCamera + "robot_heights:\n  default: 95\n", 4, "robot_heights.default",
                                 "95 mm is out of range: must be 100..200 mm");
  EXPECT_NE(what.find("at most 150 mm"), std::string::npos) << what;
  expectError(kOneCamera + "robot_heights:\n  blue: 250\n", 4, "robot_heights.blue", "must be 100..200 mm");
  expectError(kOneCamera + "robot_heights:\n  teams: {ER-Force: 15}\n", 4, "robot_heights.teams[\"ER-Force\"]",
              "must be 100..200 mm");
  expectError("cameras:\n  - {id: 0, source: a.png, fps: 0}\n", 2, "cameras[0].fps", "must be more than 0");
  expectError("cameras:\n  - {id: 0, source: a.png, fps: -30}\n", 2, "cameras[0].fps", "must be more than 0");
  expectError("cameras:\n  - {id: 0, source: a.png, threads: -1}\n", 2, "cameras[0].threads", "must be 0..256");
  expectError("cameras:\n  - {id: 256, source: a.png}\n", 2, "cameras[0].id", "must be 0..255");
  expectError(kOneCamera + "record: {raw_seconds: 0}\n", 3, "record.raw_seconds",
              "must be more than 0 s and at most 120 s");
  expectError(kOneCamera + "record: {raw_seconds: 121}\n", 3, "record.raw_seconds", "at most 120 s");
  expectError(kOneCamera + "status_interval: -1\n", 3, "status_interval", "must be 0..3600 s");
  expectError(kOneCamera + "network:\n  geometry: {timeout: 0}\n", 4, "network.geometry.timeout", "more than 0 s");
}

TEST(SiteConfigErrors, ChoicesAndAddresses) {
  expectError("cameras:\n  - {id: 0, source: a.png, bayer: rgbg}\n", 2, "cameras[0].bayer",
              "expected one of rggb, grbg, gbrg, bggr, got 'rgbg'; did you mean 'rggb'?");
  expectError("cameras:\n  - {id: 0, source: a.png, backend: cuda}\n", 2, "cameras[0].backend",
              "expected one of auto, cpu, opencl, got 'cuda'");
  expectError("cameras:\n  - {id: 0, source: a.png, bayer_sampling: half}\n", 2, "cameras[0].bayer_sampling",
              "expected one of auto, subsample, full");
  expectError(kOneCamera + "network:\n  geometry: {source: publisher2}\n", 4, "network.geometry.source",
              "expected one of auto, publisher, publish, file");
  expectError(kOneCamera + "network:\n  vision: {group: 10.0.0.1}\n", 4, "network.vision.group",
              "expected an IPv4 multicast address (224.0.0.0 to 239.255.255.255), got '10.0.0.1'");
  expectError(kOneCamera + "network:\n  vision: {group: 240.0.0.1}\n", 4, "network.vision.group", "multicast");
  expectError(kOneCamera + "network:\n  referee: {group: field-pc}\n", 4, "network.referee.group", "multicast");
  expectError(kOneCamera + "network:\n  vision: {interface: eth0}\n", 4, "network.vision.interface",
              "expected the IPv4 address of a local interface");
}

TEST(SiteConfigParse, ConsoleAddressAndTokenFile) {
  const SiteConfig c =
      parseSiteConfig(kOneCamera + "console: {http: \"0.0.0.0:9000\", token_file: /etc/dv/token}\n", "site.yaml");
  EXPECT_EQ(c.console.http, "0.0.0.0:9000");
  EXPECT_EQ(c.console.token_file, "/etc/dv/token");
  EXPECT_EQ(parseSiteConfig(kOneCamera + "console: {http: \"\"}\n", "site.yaml").console.http, "");
  std::string host;
  uint16_t port = 1;
  EXPECT_TRUE(splitListenAddress("127.0.0.1:0", host, port));
  EXPECT_EQ(host, "127.0.0.1");
  EXPECT_EQ(port, 0);
  for (const char* bad : {"localhost:8080", "127.0.0.1", "127.0.0.1:", "127.0.0.1:65536", ":80", "127.0.0.1:8o"})
    EXPECT_FALSE(splitListenAddress(bad, host, port)) << bad;
}

TEST(SiteConfigErrors, ConsoleAddress) {
  expectError(kOneCamera + "console:\n  http: localhost:8080\n", 4, "console.http",
              "expected IPv4ADDR:PORT (e.g. 127.0.0.1:8080), or \"\" for no console, got 'localhost:8080'");
  expectError(kOneCamera + "console: {htp: 1}\n", 3, "console.htp", "did you mean 'http'?");
}

TEST(SiteConfigErrors, GeometryFileNeededToPublishOrRead) {
  for (const std::string source : {"publish", "file"})
    expectError(kOneCamera + "network:\n  geometry:\n    source: " + source + "\n", 5, "network.geometry.file",
                "geometry source '" + source + "' needs a geometry file");
  EXPECT_NO_THROW(parseSiteConfig(kOneCamera + "network:\n  geometry: {source: file, file: g.json}\n", "s"));
}

TEST(SiteConfigErrors, Cameras) {
  std::string what = expectError(R"(cameras:
  - id: 1
    source: a.png
  - id: 2
    source: b.png
  - id: 1
    source: c.png
)",
                                 6, "cameras[2].id", "camera id 1 is already used by cameras[0] (line 2)");
  expectError("cameras: []\n", 1, "cameras", "the list is empty");
  expectError("network: {}\n", 1, "cameras", "missing");
  expectError("cameras:\nnetwork: {}\n", 1, "cameras", "missing or empty");
  expectError("cameras:\n  - {id: 0, source: a.png}\n  - source: b.png\n", 3, "cameras[1].id", "missing");
  expectError("cameras:\n  - {id: 0, source: a.png}\n  - id: 1\n", 3, "cameras[1].source", "missing");
  expectError("cameras:\n  - {id: 0, source: \"\"}\n", 2, "cameras[0].source", "is empty");
  expectError("cameras:\n  - id: 0\n    source: a.png\n    settings: ExposureTime=4000\n", 4,
              "cameras[0].settings", "expected a list of Name=Value items");
  expectError("cameras:\n  - id: 0\n    source: a.png\n    settings:\n      - ExposureTime: 4000\n", 5,
              "cameras[0].settings[0]", "write Name=Value, not Name: Value");
  what = expectError("cameras:\n  - id: 0\n    source: a.png\n    settings: [Gain=0, ExposureTime]\n", 4,
                     "cameras[0].settings[1]", "camera setting 'ExposureTime' is not Name=Value");
  EXPECT_EQ(what.find("site.yaml:4: key"), 0u) << what;  // the place once, not repeated
}

TEST(SiteConfigErrors, KeyGivenTwice) {
  expectError(kOneCamera + "detector: {tracking: true}\nstatus_interval: 2\ndetector: {tracking: false}\n", 5,
              "detector", "given twice (lines 3 and 5)");
}

TEST(SiteConfigErrors, YamlSyntaxAndUnreadableFiles) {
  expectError("cameras:\n  - id: 0\n    source: [a.png\nnetwork: {}\n", 4, "", "YAML syntax error");
  expectError("cameras:\n  - id: 0\n   source: a.png\n", 3, "", "YAML syntax error");
  try {
    parseSiteConfig("# nothing but a comment\n", "site.yaml");
    ADD_FAILURE() << "an empty file was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "site.yaml");
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
  }
  TempDir dir("dv_site_config");
  for (const std::string& path : {dir.file("missing.yaml"), dir.path().string()}) {
    try {
      loadSiteConfig(path);
      ADD_FAILURE() << path << " was read";
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), path);
      EXPECT_NE(std::string(e.what()).find("cannot read the site config"), std::string::npos) << e.what();
    }
  }
  // A file's errors name the file itself.
  const std::string bad = dir.file("bad.yaml");
  std::ofstream(bad) << kOneCamera << "detector:\n  ball_radius: 50\n";
  try {
    loadSiteConfig(bad);
    ADD_FAILURE() << "ball_radius 50 was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), bad + ":4");
  }
}

TEST(SiteConfigParse, NullKeepsTheDefault) {
  const SiteConfig c = parseSiteConfig(kOneCamera + "network:\n  vision:\n    port:\nrecord:\nstatus_interval: ~\n",
                                       "site.yaml");
  EXPECT_EQ(c.network.vision_port, 10006);
  EXPECT_EQ(c.status_interval, SiteConfig().status_interval);
}

TEST(SiteConfigDescribe, NamesCamerasNetworkAndHeights) {
  const SiteConfig c = parseSiteConfig(R"(cameras:
  - {id: 0, source: synthetic://two_cameras_overlap/0}
  - {id: 7, source: genicam://cam7, settings: [ExposureTime=4000], backend: cpu, threads: 2}
network: {vision: {port: 10020}, referee: {enabled: false}}
robot_heights: {blue: 150, teams: {ER-Force: 145}}
)",
                                       "site.yaml");
  const std::string text = describeSiteConfig(c);
  EXPECT_NE(text.find("site config site.yaml: 2 cameras\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  camera 0: synthetic://two_cameras_overlap/0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  camera 7: genicam://cam7 (settings ExposureTime=4000; backend cpu; 2 threads)\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("vision: 224.5.23.2:10020"), std::string::npos) << text;
  EXPECT_NE(text.find("referee: off"), std::string::npos) << text;
  EXPECT_NE(text.find("robot heights: default 140 mm; yellow by team; blue 150 mm; teams: er-force 145 mm\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("console: 127.0.0.1:8080 (token random, printed at start)\n"), std::string::npos) << text;
  const SiteConfig off = parseSiteConfig("cameras: [{id: 0, source: a.png}]\nconsole: {http: \"\"}\n", "site.yaml");
  EXPECT_NE(describeSiteConfig(off).find("console: off\n"), std::string::npos);
}

// `fps` paces a synthetic camera too (the soak runs the league's 72 fps on
// the example's cameras); without it the camera keeps its scene's rate.
TEST(SiteConfigParse, FpsSetsASyntheticCamerasRate) {
  const SiteConfig given = parseSiteConfig("cameras:\n  - {id: 0, source: synthetic://default/0, fps: 72}\n", "s");
  EXPECT_TRUE(given.cameras[0].fps_given);
  EXPECT_NE(SyntheticCamera(given.cameras[0].source, given.cameras[0].fps).describe().find("looped at 72 fps"),
            std::string::npos);
  const SiteConfig plain = parseSiteConfig("cameras:\n  - {id: 0, source: synthetic://default/0}\n", "s");
  EXPECT_FALSE(plain.cameras[0].fps_given);
  EXPECT_NE(SyntheticCamera(plain.cameras[0].source).describe().find("looped at 60 fps"), std::string::npos);
}

}  // namespace
}  // namespace dv::app

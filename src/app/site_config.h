#pragma once
// The site config of `dotvision serve`: one YAML file for a field (or the
// part of it one machine runs). Plain data with the defaults here; the YAML
// is parsed and validated at the edge (site_config.cpp) into it, every
// error naming the file, the line and the key. Every key is documented
// with its default and unit in config/site.example.yaml.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/camera_source.h"

namespace dv::app {

struct SiteCamera {
  uint32_t id = 0;       // SSL camera id (its calibration in the geometry)
  std::string source;    // as `run --source`: genicam://ID, v4l2://..., rtsp://..., files, or
                         // synthetic://SCENE/CAMERA_ID (a preset or scene file's camera, rendered live)
  std::vector<CameraSetting> settings;  // GenICam-style, applied in order
  std::string bayer = "rggb";           // layout of gray frames where the source does not say
  std::string bayer_sampling = "auto";  // auto | subsample | full
  bool full_search = false;
  std::string backend = "auto";         // auto | cpu | opencl
  int threads = 0;                      // pipeline threads for this camera; 0: an even share of the cores
  double fps = 60;                      // files and videos: frame spacing for image sequences; synthetic: the camera's rate
  bool fps_given = false;               // fps was in the file (a synthetic camera keeps its scene's rate otherwise)
  bool realtime = true;                 // files and videos: paced at their own rate
  bool loop = true;                     // files, videos, synthetic: start over at the end
  int line = 0;                         // where in the file this camera is (for messages)
};

struct SiteNetwork {
  std::string vision_group = "224.5.23.2";
  uint16_t vision_port = 10006;
  std::string interface_addr;  // local IPv4 address to publish on; "" by route
  // geometry: "auto" (a synthetic camera's scene, else the publisher), "publisher" (wait for
  // `dotvision geometry` on the vision group), "publish" (run the geometry publisher in-process from
  // geometry_file), or "file" (geometry_file, published by this process)
  std::string geometry = "auto";
  std::string geometry_file;
  double geometry_timeout = 10;  // s, waiting for network geometry
  bool referee = true;           // listen to the game controller
  std::string referee_group = "224.5.23.1";
  uint16_t referee_port = 10003;
};

struct SiteRobotHeights {
  double default_mm = 140;                 // a team not in the table
  std::optional<double> yellow_mm, blue_mm;  // fixed per color, overriding the team table
  std::map<std::string, double> teams;     // teamKey(team name) (lower case) -> mm
};

struct SiteDetector {
  bool guessed_ids = true;  // report robots whose id is a guess
  bool tracking = true;
  double ball_radius = 21.5;  // mm
};

struct SiteRecord {
  std::string raw_dir;          // "": no raw ring; else dumps go to DIR/<time>/
  double raw_seconds = 10;      // s of raw frames kept in memory per camera
  bool on_health_change = true; // dump when a camera's health changes
  std::string ssl_log;          // "": none; else every packet to this SSL log file
};

// The operator's console (a web server in `serve`): where it listens and
// where the operator's token comes from (a file, so that the config text,
// which the console shows, never holds the secret).
struct SiteConsole {
  std::string http = "127.0.0.1:8080";  // IPv4ADDR:PORT (port 0: any free port); "": no console
  std::string token_file;               // "": a random token, printed at start
};

struct SiteConfig {
  std::string path;  // the file it came from
  std::vector<SiteCamera> cameras;
  SiteNetwork network;
  SiteRobotHeights robot_heights;
  SiteDetector detector;
  SiteRecord record;
  SiteConsole console;
  double status_interval = 5;  // s between status tables on the terminal; 0: off
};

// Reads and validates `path`. Throws InputError("<path>:<line>", "key
// 'cameras[1].source': ...") on unknown keys, wrong types, out-of-range
// values, duplicate camera ids, a missing required key, or bad YAML.
SiteConfig loadSiteConfig(const std::string& path);
// The same from text (for tests and the console's edits); `name` is used in messages.
SiteConfig parseSiteConfig(const std::string& yaml_text, const std::string& name);

// A few lines for serve's start-up print and `serve --check`: the cameras
// (id, source, options that differ from the defaults), network, geometry,
// referee, robot heights, recording. Each line ends with '\n'.
std::string describeSiteConfig(const SiteConfig& config);

// Splits "IPv4ADDR:PORT" (port 0..65535); false when it is not that.
bool splitListenAddress(const std::string& text, std::string& host, uint16_t& port);

// How team names are compared (the table's keys, the referee's names):
// lower case, surrounding blanks dropped.
std::string teamKey(const std::string& name);

}  // namespace dv::app

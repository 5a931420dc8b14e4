#pragma once
// One camera's status as data: what `serve` prints every few seconds, logs
// on a change of health, and what the console reads as JSON. Filled once a
// second off the detection threads (CameraRunner::status), turned into
// words in one place (statusTable, healthChangeLine).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "live/live_camera.h"

namespace dv {

enum class Health { Ok, Degraded, Lost };
const char* healthName(Health h);

struct LatencyFigure {
  double p50_ms = -1, p99_ms = -1;  // over the last minute; -1: no samples
};

struct CameraStatus {
  uint32_t camera_id = 0;
  std::string source;   // what the source says it is
  std::string backend;  // pixel pipeline ("cpu", "opencl <device>"), "" before the first frame
  double t_unix = 0;    // when this record was made
  LiveCounters counters;
  double fps_in = 0, fps_out = 0;  // over the last second
  LatencyFigure wait;       // arrival -> taken by the processing thread
  LatencyFigure pipeline;   // pixel pipeline
  LatencyFigure detection;  // detector
  LatencyFigure total;      // arrival -> packet sent
  double blobs_per_frame = 0, robots_per_frame = 0, balls_per_frame = 0;  // last second
  double yellow_per_frame = 0, blue_per_frame = 0;
  double separation_yellow_blue = 0, separation_green_pink = 0, separation_orange_field = 0;
  double robot_height_yellow = 0, robot_height_blue = 0;  // mm in use
  // The color warnings now in force (detection/color_health.h), joined by
  // "; " ("" none), and the white lines' color last read (the cast).
  std::string color_issues;
  bool lines_valid = false;
  float lines_rgb[3] = {0, 0, 0};
  Health health = Health::Ok;
  std::string health_reason;  // "" when ok
  bool health_changed = false;  // differs from the previous record's (logged once)
};

nlohmann::json toJson(const CameraStatus& s);
// One line for one camera (run's periodic status), ending in a newline.
std::string statusLine(const CameraStatus& s);
// A compact table, a line per camera, for the terminal.
std::string statusTable(const std::vector<CameraStatus>& cameras);

}  // namespace dv

#include "live/camera_status.h"

#include <cstdio>
#include <nlohmann/json.hpp>

namespace dv {

const char* healthName(Health h) {
  switch (h) {
    case Health::Ok: return "ok";
    case Health::Degraded: return "degraded";
    case Health::Lost: return "lost";
  }
  return "?";
}

namespace {
nlohmann::json latency(const LatencyFigure& l) { return {{"p50_ms", l.p50_ms}, {"p99_ms", l.p99_ms}}; }
}  // namespace

nlohmann::json toJson(const CameraStatus& s) {
  const LiveCounters& c = s.counters;
  return {
      {"camera_id", s.camera_id},
      {"source", s.source},
      {"backend", s.backend},
      {"t_unix", s.t_unix},
      {"source_state", sourceStateName(c.state)},
      {"frames", {{"in", c.frames_in}, {"processed", c.processed}, {"dropped", c.dropped},
                  {"skipped", c.skipped}, {"gap", c.gap_frames}}},
      {"losses", c.losses},
      {"reconnects", c.reconnects},
      {"last_problem", c.last_problem},
      {"fps_in", s.fps_in},
      {"fps_out", s.fps_out},
      {"latency", {{"wait", latency(s.wait)}, {"pipeline", latency(s.pipeline)},
                   {"detection", latency(s.detection)}, {"total", latency(s.total)}}},
      {"per_frame", {{"blobs", s.blobs_per_frame}, {"robots", s.robots_per_frame}, {"balls", s.balls_per_frame},
                     {"yellow", s.yellow_per_frame}, {"blue", s.blue_per_frame}}},
      {"color_separation", {{"yellow_blue", s.separation_yellow_blue}, {"green_pink", s.separation_green_pink},
                            {"orange_field", s.separation_orange_field}}},
      {"robot_height_mm", {{"yellow", s.robot_height_yellow}, {"blue", s.robot_height_blue}}},
      {"colors", {{"issues", s.color_issues},
                  {"lines_rgb", s.lines_valid ? nlohmann::json::array({s.lines_rgb[0], s.lines_rgb[1], s.lines_rgb[2]})
                                              : nlohmann::json()}}},
      {"health", healthName(s.health)},
      {"health_reason", s.health_reason},
  };
}

std::string statusLine(const CameraStatus& s) {
  char line[512];
  std::snprintf(line, sizeof line,
                "camera %u: %s, fps in %.1f out %.1f, dropped %llu, skipped %llu, latency p50 %.2f p99 %.2f ms, "
                "%.1f robots %.1f balls per frame, %s%s%s\n",
                s.camera_id, sourceStateName(s.counters.state), s.fps_in, s.fps_out,
                static_cast<unsigned long long>(s.counters.dropped), static_cast<unsigned long long>(s.counters.skipped),
                s.total.p50_ms, s.total.p99_ms, s.robots_per_frame, s.balls_per_frame, healthName(s.health),
                s.health_reason.empty() ? "" : ": ", s.health_reason.c_str());
  return line;
}

std::string statusTable(const std::vector<CameraStatus>& cameras) {
  std::string out = "  cam  fps in/out  dropped  latency p50/p99 ms  robots  balls  health\n";
  char line[512];
  for (const CameraStatus& s : cameras) {
    std::snprintf(line, sizeof line, "  %3u  %5.1f/%-5.1f %8llu  %7.2f/%-7.2f    %6.1f  %5.1f  %s%s%s\n", s.camera_id,
                  s.fps_in, s.fps_out, static_cast<unsigned long long>(s.counters.dropped), s.total.p50_ms,
                  s.total.p99_ms, s.robots_per_frame, s.balls_per_frame, healthName(s.health),
                  s.health_reason.empty() ? "" : ": ", s.health_reason.c_str());
    out += line;
  }
  return out;
}

}  // namespace dv

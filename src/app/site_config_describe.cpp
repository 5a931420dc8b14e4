// describeSiteConfig: what serve is about to run, in a few lines; only the
// camera options that differ from the defaults are named.
#include <sstream>

#include "app/site_config.h"

namespace dv::app {

namespace {

std::string cameraOptions(const SiteCamera& c) {
  const SiteCamera defaults;
  std::ostringstream s;
  auto add = [&](const std::string& part) { s << (s.tellp() > 0 ? "; " : "") << part; };
  if (!c.settings.empty()) {
    std::string list;
    for (const CameraSetting& x : c.settings) list += (list.empty() ? "" : ", ") + x.name + "=" + x.value;
    add("settings " + list);
  }
  if (c.bayer != defaults.bayer) add("bayer " + c.bayer);
  if (c.bayer_sampling != defaults.bayer_sampling) add("bayer sampling " + c.bayer_sampling);
  if (c.full_search) add("full search");
  if (c.backend != defaults.backend) add("backend " + c.backend);
  if (c.threads > 0) add(std::to_string(c.threads) + " threads");
  if (c.fps != defaults.fps) {
    std::ostringstream f;
    f << c.fps << " fps";
    add(f.str());
  }
  if (!c.realtime) add("not paced");
  if (!c.loop) add("no loop");
  return s.str();
}

std::string mm(double v) {
  std::ostringstream s;
  s << v << " mm";
  return s.str();
}

}  // namespace

std::string describeSiteConfig(const SiteConfig& c) {
  std::ostringstream s;
  const SiteNetwork& n = c.network;
  s << "site config " << c.path << ": " << c.cameras.size() << (c.cameras.size() == 1 ? " camera\n" : " cameras\n");
  for (const SiteCamera& cam : c.cameras) {
    const std::string options = cameraOptions(cam);
    s << "  camera " << cam.id << ": " << cam.source << (options.empty() ? "" : " (" + options + ")") << "\n";
  }
  s << "vision: " << n.vision_group << ":" << n.vision_port << " on "
    << (n.interface_addr.empty() ? "the interface by route" : n.interface_addr) << "\n";
  s << "geometry: ";
  if (n.geometry == "auto")
    s << "auto (synthetic cameras: their scene; others: the publisher, waiting up to " << n.geometry_timeout
      << " s)\n";
  else if (n.geometry == "publisher")
    s << "from the geometry publisher on the vision group, waiting up to " << n.geometry_timeout << " s\n";
  else if (n.geometry == "publish")
    s << "the geometry publisher runs in this process, from " << n.geometry_file << "\n";
  else
    s << n.geometry_file << ", published by this process\n";
  s << "referee: ";
  if (n.referee)
    s << n.referee_group << ":" << n.referee_port << "\n";
  else
    s << "off\n";
  const SiteRobotHeights& h = c.robot_heights;
  s << "robot heights: default " << mm(h.default_mm) << "; yellow "
    << (h.yellow_mm ? mm(*h.yellow_mm) : std::string("by team")) << "; blue "
    << (h.blue_mm ? mm(*h.blue_mm) : std::string("by team"));
  const char* separator = "; teams: ";
  for (const auto& [team, height] : h.teams) s << separator << team << " " << mm(height), separator = ", ";
  s << "\n";
  s << "detector: guessed ids " << (c.detector.guessed_ids ? "on" : "off") << ", tracking "
    << (c.detector.tracking ? "on" : "off") << ", ball radius " << mm(c.detector.ball_radius) << "\n";
  const SiteRecord& r = c.record;
  s << "record: ";
  if (r.raw_dir.empty())
    s << "no raw frames";
  else
    s << "last " << r.raw_seconds << " s of raw frames, to " << r.raw_dir << " on SIGUSR1"
      << (r.on_health_change ? " and on health changes" : "");
  s << (r.ssl_log.empty() ? "" : "; SSL log " + r.ssl_log) << "\n";
  if (c.status_interval > 0)
    s << "status: a table every " << c.status_interval << " s\n";
  else
    s << "status: no tables\n";
  if (c.console.http.empty())
    s << "console: off\n";
  else
    s << "console: " << c.console.http << " (token "
      << (c.console.token_file.empty() ? "random, printed at start" : "from " + c.console.token_file) << ")\n";
  return s.str();
}

}  // namespace dv::app

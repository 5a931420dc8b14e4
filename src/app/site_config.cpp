// The site config's schema: which keys exist at each level, their types and
// ranges, on top of the strict reader (strict_yaml.h). The key names and
// their documentation are in config/site.example.yaml; keep both in step.
#include "app/site_config.h"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "app/strict_yaml.h"
#include "core/error.h"

namespace dv::app {

namespace {

const std::vector<std::string> kBayerLayouts = {"rggb", "grbg", "gbrg", "bggr"};

bool isIpv4(const std::string& s, in_addr* out = nullptr) {
  in_addr a{};
  if (inet_pton(AF_INET, s.c_str(), &a) != 1) return false;
  if (out) *out = a;
  return true;
}

class SiteReader {
 public:
  explicit SiteReader(const std::string& name) : y_(name) {}

  SiteConfig read(const YAML::Node& root) {
    SiteConfig c;
    c.path = y_.file();
    if (!root.IsDefined() || root.IsNull())
      throw InputError(y_.file(), "the site config is empty: it needs at least a 'cameras' list");
    bool have_cameras = false;
    y_.forEach(root, "",
               {"cameras", "network", "robot_heights", "detector", "record", "console", "status_interval"},
               [&](const std::string& key, const YAML::Node& v) {
                 if (key == "cameras") have_cameras = true, cameras(v, c.cameras);
                 if (key == "network") network(v, c.network);
                 if (key == "robot_heights") heights(v, c.robot_heights);
                 if (key == "detector") detector(v, c.detector);
                 if (key == "record") record(v, c.record);
                 if (key == "console") console(v, c.console);
                 if (key == "status_interval") c.status_interval = y_.number(v, key, 0, 3600, "s");
               });
    if (!have_cameras) y_.fail(root, "cameras", "missing or empty: the file must list at least one camera");
    return c;
  }

 private:
  void cameras(const YAML::Node& list, std::vector<SiteCamera>& out) {
    if (!list.IsSequence()) y_.fail(list, "cameras", "expected a list of cameras ('- id: 0 ...')");
    if (list.size() == 0) y_.fail(list, "cameras", "the list is empty: at least one camera is needed");
    for (size_t i = 0; i < list.size(); ++i) {
      SiteCamera cam = camera(list[i], "cameras[" + std::to_string(i) + "]");
      for (size_t j = 0; j < out.size(); ++j)
        if (out[j].id == cam.id)
          y_.fail(list[i]["id"], "cameras[" + std::to_string(i) + "].id",
                  "camera id " + std::to_string(cam.id) + " is already used by cameras[" + std::to_string(j) +
                      "] (line " + std::to_string(out[j].line) + ")");
      out.push_back(std::move(cam));
    }
  }

  SiteCamera camera(const YAML::Node& n, const std::string& path) {
    SiteCamera cam;
    cam.line = n.Mark().line + 1;
    bool have_id = false, have_source = false;
    if (!n.IsMap()) y_.fail(n, path, "expected a camera: a map with at least 'id' and 'source'");
    y_.forEach(n, path,
               {"id", "source", "settings", "bayer", "bayer_sampling", "full_search", "backend", "threads",
                "fps", "realtime", "loop"},
               [&](const std::string& key, const YAML::Node& v) {
                 const std::string k = key.substr(path.size() + 1);
                 if (k == "id") have_id = true, cam.id = uint32_t(y_.integer(v, key, 0, 255));
                 if (k == "source") {
                   cam.source = y_.text(v, key);
                   if (cam.source.empty()) y_.fail(v, key, "is empty: name the camera, file or synthetic scene");
                   have_source = true;
                 }
                 if (k == "settings") cam.settings = settings(v, key);
                 if (k == "bayer") cam.bayer = y_.choice(v, key, kBayerLayouts);
                 if (k == "bayer_sampling") cam.bayer_sampling = y_.choice(v, key, {"auto", "subsample", "full"});
                 if (k == "full_search") cam.full_search = y_.boolean(v, key);
                 if (k == "backend") cam.backend = y_.choice(v, key, {"auto", "cpu", "opencl"});
                 if (k == "threads") cam.threads = int(y_.integer(v, key, 0, 256));
                 if (k == "fps") cam.fps = y_.number(v, key, 0, 1000, "frames/s", true), cam.fps_given = true;
                 if (k == "realtime") cam.realtime = y_.boolean(v, key);
                 if (k == "loop") cam.loop = y_.boolean(v, key);
               });
    if (!have_id) y_.fail(n, path + ".id", "missing: every camera needs its SSL camera id");
    if (!have_source) y_.fail(n, path + ".source", "missing: every camera needs a source");
    return cam;
  }

  // An ordered list of "Name=Value" (order matters: a selector before the value it selects).
  std::vector<CameraSetting> settings(const YAML::Node& list, const std::string& key) {
    if (!list.IsSequence())
      y_.fail(list, key, "expected a list of Name=Value items, e.g. [ExposureTime=4000, Gain=0]");
    std::vector<CameraSetting> out;
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string item_key = key + "[" + std::to_string(i) + "]";
      if (!list[i].IsScalar())
        y_.fail(list[i], item_key, "expected Name=Value text (e.g. ExposureTime=4000), got a " +
                                       std::string(list[i].IsMap() ? "map: write Name=Value, not Name: Value"
                                                                   : "list"));
      const std::string origin = y_.where(list[i]);
      try {
        out.push_back(parseCameraSetting(list[i].Scalar(), origin));
      } catch (const InputError& e) {
        const std::string what = e.what();
        y_.fail(list[i], item_key, what.substr(std::min(what.size(), origin.size() + 2)));
      }
    }
    return out;
  }

  void network(const YAML::Node& n, SiteNetwork& net) {
    y_.forEach(n, "network", {"vision", "geometry", "referee"}, [&](const std::string& key, const YAML::Node& v) {
      if (key == "network.vision")
        y_.forEach(v, key, {"group", "port", "interface"}, [&](const std::string& k, const YAML::Node& x) {
          if (k == key + ".group") net.vision_group = multicastGroup(x, k);
          if (k == key + ".port") net.vision_port = port(x, k);
          if (k == key + ".interface") {
            net.interface_addr = y_.text(x, k);
            if (!net.interface_addr.empty() && !isIpv4(net.interface_addr))
              y_.fail(x, k, "expected the IPv4 address of a local interface (or \"\" by route), got '" +
                                net.interface_addr + "'");
          }
        });
      if (key == "network.geometry") geometry(v, key, net);
      if (key == "network.referee")
        y_.forEach(v, key, {"enabled", "group", "port"}, [&](const std::string& k, const YAML::Node& x) {
          if (k == key + ".enabled") net.referee = y_.boolean(x, k);
          if (k == key + ".group") net.referee_group = multicastGroup(x, k);
          if (k == key + ".port") net.referee_port = port(x, k);
        });
    });
  }

  void geometry(const YAML::Node& n, const std::string& path, SiteNetwork& net) {
    YAML::Node source_node;
    y_.forEach(n, path, {"source", "file", "timeout"}, [&](const std::string& k, const YAML::Node& x) {
      if (k == path + ".source")
        net.geometry = y_.choice(x, k, {"auto", "publisher", "publish", "file"}), source_node.reset(x);
      if (k == path + ".file") net.geometry_file = y_.text(x, k);
      if (k == path + ".timeout") net.geometry_timeout = y_.number(x, k, 0, 600, "s", true);
    });
    if ((net.geometry == "publish" || net.geometry == "file") && net.geometry_file.empty())
      y_.fail(source_node, path + ".file",
              "missing: geometry source '" + net.geometry + "' needs a geometry file (field and calibrations)");
  }

  uint16_t port(const YAML::Node& n, const std::string& key) { return uint16_t(y_.integer(n, key, 1, 65535)); }

  std::string multicastGroup(const YAML::Node& n, const std::string& key) {
    const std::string g = y_.text(n, key);
    in_addr a{};
    if (!isIpv4(g, &a) || (ntohl(a.s_addr) >> 28) != 0xE)
      y_.fail(n, key, "expected an IPv4 multicast address (224.0.0.0 to 239.255.255.255), got '" + g + "'");
    return g;
  }

  double height(const YAML::Node& n, const std::string& key) {
    return y_.number(n, key, 100, 200, "mm", false, "robots in the league are at most 150 mm tall");
  }

  void heights(const YAML::Node& n, SiteRobotHeights& h) {
    y_.forEach(n, "robot_heights", {"default", "yellow", "blue", "teams"},
               [&](const std::string& key, const YAML::Node& v) {
                 if (key == "robot_heights.default") h.default_mm = height(v, key);
                 if (key == "robot_heights.yellow") h.yellow_mm = height(v, key);
                 if (key == "robot_heights.blue") h.blue_mm = height(v, key);
                 if (key == "robot_heights.teams") teams(v, key, h.teams);
               });
  }

  void teams(const YAML::Node& n, const std::string& path, std::map<std::string, double>& out) {
    if (!n.IsMap()) y_.fail(n, path, "expected a map of team name: height in mm, e.g. {\"ER-Force\": 150}");
    std::map<std::string, std::pair<std::string, int>> seen;  // key -> (name as written, line)
    for (const auto& kv : n) {
      const std::string name = kv.first.IsScalar() ? kv.first.Scalar() : "";
      const std::string key = path + "[\"" + name + "\"]";
      const std::string team = teamKey(name);
      if (team.empty()) y_.fail(kv.first, key, "a team name is empty");
      const int line = kv.first.Mark().line + 1;
      if (const auto it = seen.find(team); it != seen.end())
        y_.fail(kv.first, key,
                "the same team as '" + it->second.first + "' (line " + std::to_string(it->second.second) +
                    "): team names are matched ignoring case");
      seen[team] = {name, line};
      if (kv.second.IsNull()) y_.fail(kv.first, key, "no height: write the team's robot height in mm");
      out[team] = height(kv.second, key);
    }
  }

  void detector(const YAML::Node& n, SiteDetector& d) {
    y_.forEach(n, "detector", {"guessed_ids", "tracking", "ball_radius"},
               [&](const std::string& key, const YAML::Node& v) {
                 if (key == "detector.guessed_ids") d.guessed_ids = y_.boolean(v, key);
                 if (key == "detector.tracking") d.tracking = y_.boolean(v, key);
                 if (key == "detector.ball_radius")
                   d.ball_radius = y_.number(v, key, 15, 30, "mm", false, "the league's ball is 21.5 mm");
               });
  }

  void record(const YAML::Node& n, SiteRecord& r) {
    y_.forEach(n, "record", {"raw_dir", "raw_seconds", "on_health_change", "ssl_log"},
               [&](const std::string& key, const YAML::Node& v) {
                 if (key == "record.raw_dir") r.raw_dir = y_.text(v, key);
                 if (key == "record.raw_seconds") r.raw_seconds = y_.number(v, key, 0, 120, "s", true);
                 if (key == "record.on_health_change") r.on_health_change = y_.boolean(v, key);
                 if (key == "record.ssl_log") r.ssl_log = y_.text(v, key);
               });
  }

  void console(const YAML::Node& n, SiteConsole& c) {
    y_.forEach(n, "console", {"http", "token_file"}, [&](const std::string& key, const YAML::Node& v) {
      if (key == "console.http") {
        c.http = y_.text(v, key);
        std::string host;
        uint16_t port = 0;
        if (!c.http.empty() && !splitListenAddress(c.http, host, port))
          y_.fail(v, key, "expected IPv4ADDR:PORT (e.g. 127.0.0.1:8080), or \"\" for no console, got '" + c.http + "'");
      }
      if (key == "console.token_file") c.token_file = y_.text(v, key);
    });
  }

  StrictYaml y_;
};

}  // namespace

bool splitListenAddress(const std::string& text, std::string& host, uint16_t& port) {
  const size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon + 1 == text.size() || colon + 6 < text.size()) return false;
  const std::string digits = text.substr(colon + 1);
  if (digits.find_first_not_of("0123456789") != std::string::npos) return false;
  const long p = std::stol(digits);
  if (p > 65535 || !isIpv4(text.substr(0, colon))) return false;
  host = text.substr(0, colon);
  port = static_cast<uint16_t>(p);
  return true;
}

std::string teamKey(const std::string& name) {
  const size_t a = name.find_first_not_of(" \t"), b = name.find_last_not_of(" \t");
  std::string key = a == std::string::npos ? std::string() : name.substr(a, b - a + 1);
  for (char& c : key) c = char(std::tolower(static_cast<unsigned char>(c)));
  return key;
}

SiteConfig parseSiteConfig(const std::string& yaml_text, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    const std::string where = e.mark.line < 0 ? name : name + ":" + std::to_string(e.mark.line + 1);
    throw InputError(where, "YAML syntax error: " + e.msg +
                                (e.mark.column < 0 ? "" : " (column " + std::to_string(e.mark.column + 1) + ")"));
  }
  return SiteReader(name).read(root);
}

SiteConfig loadSiteConfig(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path, "cannot read the site config: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot read the site config: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "cannot read the site config: read error");
  return parseSiteConfig(text.str(), path);
}

}  // namespace dv::app

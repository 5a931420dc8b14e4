// Scene files: strict YAML. Every key is known, every value has the right
// type and a sane range; otherwise one InputError naming the file, the line
// and column, and what is wrong.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "synth/embedded_scenes.h"
#include "synth/scene.h"

namespace dv {

namespace {

class SceneReader {
 public:
  explicit SceneReader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& what) const {
    const YAML::Mark m = at.Mark();
    if (m.line < 0) throw InputError(source_, what);
    throw InputError(source_, "line " + std::to_string(m.line + 1) + ", column " +
                                  std::to_string(m.column + 1) + ": " + what);
  }

  // Rejects keys outside `known`; `where` names the map in messages.
  void checkKeys(const YAML::Node& map, const std::string& where,
                 std::initializer_list<const char*> known) const {
    if (!map.IsMap()) fail(map, where + ": expected a map of keys");
    for (const auto& kv : map) {
      const std::string key = kv.first.Scalar();
      if (std::find_if(known.begin(), known.end(), [&](const char* k) { return key == k; }) ==
          known.end()) {
        std::string list;
        for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
        fail(kv.first, "unknown key '" + key + "' in " + where + " (known: " + list + ")");
      }
    }
  }

  double number(const YAML::Node& n, const std::string& what, double lo = -1e300,
                double hi = 1e300) const {
    if (!n.IsScalar()) fail(n, what + ": expected a number");
    double v = 0;
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(n, what + ": expected a number, got '" + n.Scalar() + "'");
    }
    if (!std::isfinite(v)) fail(n, what + ": expected a finite number");
    if (v < lo || v > hi) {
      std::ostringstream s;
      s << what << ": " << v << " is outside [" << lo << ", " << hi << "]";
      fail(n, s.str());
    }
    return v;
  }

  int integer(const YAML::Node& n, const std::string& what, int lo, int hi) const {
    if (!n.IsScalar()) fail(n, what + ": expected an integer");
    long long v = 0;
    try {
      v = n.as<long long>();
    } catch (const YAML::Exception&) {
      fail(n, what + ": expected an integer, got '" + n.Scalar() + "'");
    }
    if (v < lo || v > hi)
      fail(n, what + ": " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
                  std::to_string(hi) + "]");
    return int(v);
  }

  uint64_t seed(const YAML::Node& n, const std::string& what) const {
    if (!n.IsScalar()) fail(n, what + ": expected a non-negative integer");
    try {
      return n.as<uint64_t>();
    } catch (const YAML::Exception&) {
      fail(n, what + ": expected a non-negative integer, got '" + n.Scalar() + "'");
    }
  }

  bool boolean(const YAML::Node& n, const std::string& what) const {
    if (!n.IsScalar()) fail(n, what + ": expected true or false");
    try {
      return n.as<bool>();
    } catch (const YAML::Exception&) {
      fail(n, what + ": expected true or false, got '" + n.Scalar() + "'");
    }
  }

  std::string text(const YAML::Node& n, const std::string& what) const {
    if (!n.IsScalar()) fail(n, what + ": expected a string");
    return n.Scalar();
  }

  std::vector<double> numbers(const YAML::Node& n, const std::string& what, size_t min_count,
                              size_t max_count, double lo = -1e300, double hi = 1e300) const {
    if (!n.IsSequence() || n.size() < min_count || n.size() > max_count) {
      const std::string count = min_count == max_count
                                    ? std::to_string(min_count)
                                    : std::to_string(min_count) + " or " + std::to_string(max_count);
      fail(n, what + ": expected a list of " + count + " numbers");
    }
    std::vector<double> out;
    for (size_t i = 0; i < n.size(); ++i) out.push_back(number(n[i], what, lo, hi));
    return out;
  }

  FieldPoint point3(const YAML::Node& n, const std::string& what) const {
    const auto v = numbers(n, what, 3, 3, -1e6, 1e6);
    return {v[0], v[1], v[2]};
  }
  FieldMm point2(const YAML::Node& n, const std::string& what) const {
    const auto v = numbers(n, what, 2, 2, -1e6, 1e6);
    return {v[0], v[1]};
  }
  Rgb color(const YAML::Node& n, const std::string& what) const {
    const auto v = numbers(n, what, 3, 3, 0, 10000);
    return {v[0], v[1], v[2]};
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

// Calls fn(value) when map has `key`.
template <typename Fn>
void with(const YAML::Node& map, const char* key, Fn fn) {
  const YAML::Node n = map[key];
  if (n.IsDefined() && !n.IsNull()) fn(n);
}

FieldModel readField(const SceneReader& r, const YAML::Node& n) {
  auto division = [&](const YAML::Node& d) {
    const std::string name = r.text(d, "field");
    if (name == "division_a" || name == "a" || name == "A") return FieldModel::divisionA();
    if (name == "division_b" || name == "b" || name == "B") return FieldModel::divisionB();
    r.fail(d, "field: unknown division '" + name + "' (known: division_a, division_b)");
  };
  if (n.IsScalar()) return division(n);
  r.checkKeys(n, "field",
              {"division", "field_length", "field_width", "goal_width", "goal_depth",
               "boundary_width", "boundary_width_goal_line", "penalty_area_depth",
               "penalty_area_width", "center_circle_radius", "line_thickness", "goal_height",
               "ball_radius"});
  FieldModel f = FieldModel::divisionB();
  with(n, "division", [&](const YAML::Node& d) { f = division(d); });
  auto dim = [&](const char* key, int& out, int lo, int hi) {
    with(n, key, [&](const YAML::Node& v) { out = r.integer(v, std::string("field.") + key, lo, hi); });
  };
  dim("field_length", f.field_length, 1000, 30000);
  dim("field_width", f.field_width, 1000, 30000);
  dim("goal_width", f.goal_width, 100, 5000);
  dim("goal_depth", f.goal_depth, 10, 1000);
  dim("boundary_width", f.boundary_width, 0, 3000);
  dim("boundary_width_goal_line", f.boundary_width_goal_line, 0, 3000);
  dim("penalty_area_depth", f.penalty_area_depth, 100, 10000);
  dim("penalty_area_width", f.penalty_area_width, 100, 20000);
  dim("center_circle_radius", f.center_circle_radius, 10, 5000);
  dim("line_thickness", f.line_thickness, 1, 200);
  dim("goal_height", f.goal_height, 10, 1000);
  with(n, "ball_radius",
       [&](const YAML::Node& v) { f.ball_radius = r.number(v, "field.ball_radius", 5, 200); });
  f.generateMarkings();
  return f;
}

SceneCamera readCamera(const SceneReader& r, const YAML::Node& n, size_t index) {
  const std::string where = "cameras[" + std::to_string(index) + "]";
  r.checkKeys(n, where,
              {"id", "position", "look_at", "up", "focal_length", "distortion", "lens",
               "principal_offset", "size", "principal_point", "q", "t"});
  const uint32_t id = uint32_t(
      n["id"].IsDefined() ? r.integer(n["id"], where + ".id", 0, 1000) : int(index));
  if (!n["size"].IsDefined()) r.fail(n, where + ": missing key 'size' ([width, height] in px)");
  const auto size = r.numbers(n["size"], where + ".size", 2, 2, 2, 8192);
  if (size[0] != std::floor(size[0]) || size[1] != std::floor(size[1]))
    r.fail(n["size"], where + ".size: expected whole pixels");
  if (!n["focal_length"].IsDefined()) r.fail(n, where + ": missing key 'focal_length' (px)");
  const double focal = r.number(n["focal_length"], where + ".focal_length", 1, 1e6);
  double k = 0;
  with(n, "distortion", [&](const YAML::Node& v) { k = r.number(v, where + ".distortion", -10, 10); });
  LensTerms lens;  // [k2, k3, p1, p2] beyond the league's model (camera_model.h)
  with(n, "lens", [&](const YAML::Node& v) {
    const auto l = r.numbers(v, where + ".lens", 4, 4, -10, 10);
    lens = {l[0], l[1], l[2], l[3]};
  });
  const bool pose = n["position"].IsDefined() || n["look_at"].IsDefined();
  const bool explicit_pose = n["q"].IsDefined() || n["t"].IsDefined();
  if (pose && explicit_pose)
    r.fail(n, where + ": give either position/look_at or q/t, not both");
  if (pose) {
    if (!n["position"].IsDefined()) r.fail(n, where + ": missing key 'position' ([x, y, z] mm)");
    if (!n["look_at"].IsDefined()) r.fail(n, where + ": missing key 'look_at' ([x, y, z] mm)");
    if (n["principal_point"].IsDefined())
      r.fail(n["principal_point"], where + ": with position/look_at use principal_offset");
    const FieldPoint pos = r.point3(n["position"], where + ".position");
    const FieldPoint at = r.point3(n["look_at"], where + ".look_at");
    FieldPoint up{};
    with(n, "up", [&](const YAML::Node& v) { up = r.point3(v, where + ".up"); });
    ImagePx offset{};
    with(n, "principal_offset", [&](const YAML::Node& v) {
      const FieldMm o = r.point2(v, where + ".principal_offset");
      offset = {o.x, o.y};
    });
    if (pos.z <= 0) r.fail(n["position"], where + ".position: the camera must be above the field");
    try {
      SceneCamera c = makeCamera(id, pos, at, focal, k, offset, uint32_t(size[0]), uint32_t(size[1]), up);
      c.calib.lens = lens;
      return c;
    } catch (const std::invalid_argument& e) {
      r.fail(n, where + ": " + e.what());
    }
  }
  if (!explicit_pose) r.fail(n, where + ": give position and look_at (or q and t)");
  if (!n["q"].IsDefined() || !n["t"].IsDefined()) r.fail(n, where + ": give both q and t");
  const auto q = r.numbers(n["q"], where + ".q", 4, 4, -10, 10);
  const auto t = r.numbers(n["t"], where + ".t", 3, 3, -1e6, 1e6);
  if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0) r.fail(n["q"], where + ".q: zero quaternion");
  SceneCamera c;
  c.calib.camera_id = id;
  c.calib.focal_length = focal;
  c.calib.distortion = k;
  c.calib.lens = lens;
  c.calib.principal_point_x = (size[0] - 1) / 2;
  c.calib.principal_point_y = (size[1] - 1) / 2;
  with(n, "principal_point", [&](const YAML::Node& v) {
    const FieldMm p = r.point2(v, where + ".principal_point");
    c.calib.principal_point_x = p.x, c.calib.principal_point_y = p.y;
  });
  if (n["principal_offset"].IsDefined())
    r.fail(n["principal_offset"], where + ": with q/t use principal_point");
  c.calib.q0 = q[0], c.calib.q1 = q[1], c.calib.q2 = q[2], c.calib.q3 = q[3];
  c.calib.tx = t[0], c.calib.ty = t[1], c.calib.tz = t[2];
  c.calib.image_width = uint32_t(size[0]);
  c.calib.image_height = uint32_t(size[1]);
  return c;
}

Team readTeam(const SceneReader& r, const YAML::Node& n, const std::string& what) {
  const std::string t = r.text(n, what);
  if (t == "yellow") return Team::Yellow;
  if (t == "blue") return Team::Blue;
  r.fail(n, what + ": unknown team '" + t + "' (known: yellow, blue)");
}

SceneRobot readRobot(const SceneReader& r, const YAML::Node& n, size_t index) {
  const std::string where = "robots[" + std::to_string(index) + "]";
  r.checkKeys(n, where,
              {"team", "id", "position", "orientation", "height", "velocity", "angular_velocity"});
  for (const char* key : {"team", "id", "position"})
    if (!n[key].IsDefined()) r.fail(n, where + ": missing key '" + key + "'");
  SceneRobot robot;
  robot.team = readTeam(r, n["team"], where + ".team");
  robot.id = r.integer(n["id"], where + ".id", 0, 15);
  robot.position = r.point2(n["position"], where + ".position");
  with(n, "orientation", [&](const YAML::Node& v) { robot.orientation = r.number(v, where + ".orientation", -100, 100); });
  with(n, "height", [&](const YAML::Node& v) { robot.height = r.number(v, where + ".height", 20, 300); });
  with(n, "velocity", [&](const YAML::Node& v) { robot.velocity = r.point2(v, where + ".velocity"); });
  with(n, "angular_velocity", [&](const YAML::Node& v) {
    robot.angular_velocity = r.number(v, where + ".angular_velocity", -100, 100);
  });
  return robot;
}

SceneBall readBall(const SceneReader& r, const YAML::Node& n, double radius) {
  r.checkKeys(n, "ball", {"position", "velocity", "kicks", "wall_restitution", "present"});
  SceneBall b;
  b.position.z = radius;
  with(n, "position", [&](const YAML::Node& v) {
    const auto p = r.numbers(v, "ball.position", 2, 3, -1e6, 1e6);
    b.position = {p[0], p[1], p.size() == 3 ? p[2] : radius};
  });
  with(n, "velocity", [&](const YAML::Node& v) {
    const auto p = r.numbers(v, "ball.velocity", 2, 3, -1e5, 1e5);
    b.velocity = {p[0], p[1], p.size() == 3 ? p[2] : 0};
  });
  with(n, "kicks", [&](const YAML::Node& list) {
    if (!list.IsSequence()) r.fail(list, "ball.kicks: expected a list of {t, velocity}");
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string where = "ball.kicks[" + std::to_string(i) + "]";
      const YAML::Node k = list[i];
      r.checkKeys(k, where, {"t", "velocity"});
      if (!k["t"].IsDefined() || !k["velocity"].IsDefined())
        r.fail(k, where + ": needs 't' (s) and 'velocity' ([vx, vy(, vz)] mm/s)");
      BallKick kick;
      kick.t = r.number(k["t"], where + ".t", 1e-9, 1e6);
      if (!b.kicks.empty() && kick.t <= b.kicks.back().t)
        r.fail(k["t"], where + ".t: kicks must be in increasing time");
      const auto v = r.numbers(k["velocity"], where + ".velocity", 2, 3, -1e5, 1e5);
      kick.velocity = {v[0], v[1], v.size() == 3 ? v[2] : 0};
      b.kicks.push_back(kick);
    }
  });
  with(n, "wall_restitution", [&](const YAML::Node& v) {
    b.wall_restitution = r.number(v, "ball.wall_restitution", 0, 1);
  });
  with(n, "present", [&](const YAML::Node& v) { b.present = r.boolean(v, "ball.present"); });
  return b;
}

LightPatch readPatch(const SceneReader& r, const YAML::Node& n, const std::string& where,
                     double default_gain) {
  r.checkKeys(n, where, {"center", "radii", "angle", "gain", "softness"});
  LightPatch p;
  p.gain = default_gain;
  if (!n["center"].IsDefined()) r.fail(n, where + ": missing key 'center' ([x, y] mm)");
  p.center = r.point2(n["center"], where + ".center");
  with(n, "radii", [&](const YAML::Node& v) {
    const auto radii = r.numbers(v, where + ".radii", 2, 2, 1, 1e5);
    p.radius_x = radii[0], p.radius_y = radii[1];
  });
  with(n, "angle", [&](const YAML::Node& v) { p.angle = r.number(v, where + ".angle", -100, 100); });
  with(n, "gain", [&](const YAML::Node& v) { p.gain = r.number(v, where + ".gain", 0, 20); });
  with(n, "softness", [&](const YAML::Node& v) { p.softness = r.number(v, where + ".softness", 0, 1.9); });
  return p;
}

SceneLighting readLighting(const SceneReader& r, const YAML::Node& n) {
  r.checkKeys(n, "lighting",
              {"exposure", "white_balance", "saturation", "gamma", "uneven_ratio", "uneven_direction", "vignetting",
               "sun_patches", "shadows", "object_shadow", "flicker_amplitude",
               "flicker_frequency", "exposure_time"});
  SceneLighting l;
  with(n, "exposure", [&](const YAML::Node& v) { l.exposure = r.number(v, "lighting.exposure", 0, 100); });
  with(n, "white_balance", [&](const YAML::Node& v) { l.white_balance = r.color(v, "lighting.white_balance"); });
  with(n, "saturation", [&](const YAML::Node& v) { l.saturation = r.number(v, "lighting.saturation", 0, 3); });
  with(n, "gamma", [&](const YAML::Node& v) { l.gamma = r.number(v, "lighting.gamma", 0.2, 5); });
  with(n, "uneven_ratio", [&](const YAML::Node& v) { l.uneven_ratio = r.number(v, "lighting.uneven_ratio", 1, 100); });
  with(n, "uneven_direction", [&](const YAML::Node& v) { l.uneven_direction = r.number(v, "lighting.uneven_direction", -100, 100); });
  with(n, "vignetting", [&](const YAML::Node& v) { l.vignetting = r.number(v, "lighting.vignetting", 0, 0.95); });
  auto patches = [&](const char* key, double gain, std::vector<LightPatch>& out) {
    with(n, key, [&](const YAML::Node& v) {
      if (!v.IsSequence()) r.fail(v, std::string("lighting.") + key + ": expected a list");
      for (size_t i = 0; i < v.size(); ++i)
        out.push_back(readPatch(r, v[i], std::string("lighting.") + key + "[" + std::to_string(i) + "]", gain));
    });
  };
  patches("sun_patches", 1.8, l.sun_patches);
  patches("shadows", 0.6, l.shadows);
  with(n, "object_shadow", [&](const YAML::Node& v) { l.object_shadow = r.number(v, "lighting.object_shadow", 0, 1); });
  with(n, "flicker_amplitude", [&](const YAML::Node& v) { l.flicker_amplitude = r.number(v, "lighting.flicker_amplitude", 0, 1); });
  with(n, "flicker_frequency", [&](const YAML::Node& v) { l.flicker_frequency = r.number(v, "lighting.flicker_frequency", 0, 100000); });
  with(n, "exposure_time", [&](const YAML::Node& v) { l.exposure_time = r.number(v, "lighting.exposure_time", 0, 1); });
  return l;
}

SceneMaterials readMaterials(const SceneReader& r, const YAML::Node& n) {
  r.checkKeys(n, "materials",
              {"carpet", "carpet_texture", "line", "wall", "goal", "floor", "background",
               "robot_top", "robot_body", "yellow", "blue", "green", "pink", "ball"});
  SceneMaterials m;
  auto col = [&](const char* key, Rgb& out) {
    with(n, key, [&](const YAML::Node& v) { out = r.color(v, std::string("materials.") + key); });
  };
  col("carpet", m.carpet);
  with(n, "carpet_texture", [&](const YAML::Node& v) { m.carpet_texture = r.number(v, "materials.carpet_texture", 0, 1); });
  col("line", m.line);
  col("wall", m.wall);
  col("goal", m.goal);
  col("floor", m.floor);
  col("background", m.background);
  col("robot_top", m.robot_top);
  col("robot_body", m.robot_body);
  col("yellow", m.yellow);
  col("blue", m.blue);
  col("green", m.green);
  col("pink", m.pink);
  col("ball", m.ball);
  return m;
}

SceneSpec readScene(const SceneReader& r, const YAML::Node& root) {
  if (!root.IsDefined() || root.IsNull()) r.fail(root, "the scene is empty");
  r.checkKeys(root, "scene",
              {"name", "seed", "field", "cameras", "robots", "random_robots", "ball",
               "random_motion", "materials", "lighting", "noise_sigma", "shot_noise",
               "lens_blur_px", "frames", "fps", "motion_blur", "motion_blur_samples", "bayer",
               "png", "antialias", "jpeg_quality", "clutter"});
  SceneSpec s;
  with(root, "name", [&](const YAML::Node& v) { s.name = r.text(v, "name"); });
  with(root, "seed", [&](const YAML::Node& v) { s.seed = r.seed(v, "seed"); });
  with(root, "field", [&](const YAML::Node& v) { s.field = readField(r, v); });
  if (!root["cameras"].IsDefined()) r.fail(root, "missing key 'cameras'");
  const YAML::Node cams = root["cameras"];
  if (!cams.IsSequence() || cams.size() == 0) r.fail(cams, "cameras: expected a non-empty list");
  for (size_t i = 0; i < cams.size(); ++i) {
    s.cameras.push_back(readCamera(r, cams[i], i));
    for (size_t j = 0; j < i; ++j)
      if (s.cameras[j].calib.camera_id == s.cameras[i].calib.camera_id)
        r.fail(cams[i], "cameras[" + std::to_string(i) + "]: camera id " +
                            std::to_string(s.cameras[i].calib.camera_id) + " appears twice");
  }
  with(root, "ball", [&](const YAML::Node& v) { s.ball = readBall(r, v, s.field.ball_radius); });
  if (!root["ball"].IsDefined()) s.ball.present = false;
  with(root, "robots", [&](const YAML::Node& v) {
    if (!v.IsSequence()) r.fail(v, "robots: expected a list");
    for (size_t i = 0; i < v.size(); ++i) {
      s.robots.push_back(readRobot(r, v[i], i));
      for (size_t j = 0; j < i; ++j)
        if (s.robots[j].team == s.robots[i].team && s.robots[j].id == s.robots[i].id)
          r.fail(v[i], "robots[" + std::to_string(i) + "]: this team already has id " +
                           std::to_string(s.robots[i].id));
    }
  });
  with(root, "clutter", [&](const YAML::Node& v) {
    if (!v.IsSequence()) r.fail(v, "clutter: expected a list");
    for (size_t i = 0; i < v.size(); ++i) {
      const std::string where = "clutter[" + std::to_string(i) + "]";
      r.checkKeys(v[i], where, {"min", "max", "color"});
      for (const char* k : {"min", "max", "color"})
        if (!v[i][k].IsDefined()) r.fail(v[i], where + ": missing key '" + k + "'");
      SceneBox b{r.point3(v[i]["min"], where + ".min"), r.point3(v[i]["max"], where + ".max"),
                 r.color(v[i]["color"], where + ".color")};
      if (!(b.min.x < b.max.x && b.min.y < b.max.y && b.min.z < b.max.z && b.min.z >= 0))
        r.fail(v[i], where + ": min must lie below max on every axis, and not under the floor");
      s.clutter.push_back(b);
    }
  });
  with(root, "materials", [&](const YAML::Node& v) { s.materials = readMaterials(r, v); });
  with(root, "lighting", [&](const YAML::Node& v) { s.lighting = readLighting(r, v); });
  with(root, "noise_sigma", [&](const YAML::Node& v) { s.noise_sigma = r.number(v, "noise_sigma", 0, 100); });
  with(root, "shot_noise", [&](const YAML::Node& v) { s.shot_noise = r.number(v, "shot_noise", 0, 100); });
  with(root, "lens_blur_px", [&](const YAML::Node& v) { s.lens_blur_px = r.number(v, "lens_blur_px", 0, 50); });
  with(root, "frames", [&](const YAML::Node& v) { s.frames = r.integer(v, "frames", 1, 100000); });
  with(root, "fps", [&](const YAML::Node& v) { s.fps = r.number(v, "fps", 0.01, 10000); });
  with(root, "motion_blur", [&](const YAML::Node& v) { s.motion_blur = r.boolean(v, "motion_blur"); });
  with(root, "motion_blur_samples", [&](const YAML::Node& v) { s.motion_blur_samples = r.integer(v, "motion_blur_samples", 1, 64); });
  with(root, "bayer", [&](const YAML::Node& v) {
    // true / false, or the layout of the mosaic (rggb, grbg, gbrg, bggr).
    static const char* const kLayouts[] = {"rggb", "grbg", "gbrg", "bggr"};
    for (int k = 0; k < 4; ++k)
      if (v.IsScalar() && v.Scalar() == kLayouts[k]) {
        s.bayer = true;
        s.bayer_layout = static_cast<BayerLayout>(k);
        return;
      }
    bool on = false;
    if (!v.IsScalar() || !YAML::convert<bool>::decode(v, on))
      r.fail(v, "bayer: expected true, false, rggb, grbg, gbrg or bggr, got '" + v.Scalar() + "'");
    s.bayer = on;
  });
  with(root, "png", [&](const YAML::Node& v) { s.write_png = r.boolean(v, "png"); });
  with(root, "antialias", [&](const YAML::Node& v) { s.antialias = r.integer(v, "antialias", 1, 8); });
  with(root, "jpeg_quality", [&](const YAML::Node& v) {
    s.jpeg_quality = r.integer(v, "jpeg_quality", 0, 100);
    if (s.jpeg_quality > 0 && s.bayer) r.fail(v, "jpeg_quality: JPEG frames are RGB, set bayer: false");
  });

  // Random content last: it depends on cameras, ball and explicit robots.
  // random_robots: one block or a list of blocks (e.g. one per camera).
  with(root, "random_robots", [&](const YAML::Node& blocks) {
    const bool list = blocks.IsSequence();
    for (size_t i = 0; i < (list ? blocks.size() : 1); ++i) {
      const YAML::Node v = list ? blocks[i] : blocks;
      const std::string where = list ? "random_robots[" + std::to_string(i) + "]" : "random_robots";
      r.checkKeys(v, where, {"yellow", "blue", "camera", "seed", "min_distance", "margin_px"});
      const int yellow = v["yellow"].IsDefined() ? r.integer(v["yellow"], where + ".yellow", 0, 16) : 0;
      const int blue = v["blue"].IsDefined() ? r.integer(v["blue"], where + ".blue", 0, 16) : 0;
      const int cam = v["camera"].IsDefined()
                          ? r.integer(v["camera"], where + ".camera (index into cameras)", 0,
                                      int(s.cameras.size()) - 1)
                          : 0;
      const uint64_t seed =
          v["seed"].IsDefined() ? r.seed(v["seed"], where + ".seed") : s.seed + 7919 * i;
      const double min_distance =
          v["min_distance"].IsDefined() ? r.number(v["min_distance"], where + ".min_distance", 180, 5000)
                                        : 200;
      const double margin =
          v["margin_px"].IsDefined() ? r.number(v["margin_px"], where + ".margin_px", 0, 5000) : 40;
      try {
        const auto added = placeRandomRobots(s, size_t(cam), yellow, blue, seed, min_distance, margin);
        s.robots.insert(s.robots.end(), added.begin(), added.end());
      } catch (const std::invalid_argument& e) {
        r.fail(v, where + ": " + e.what());
      }
    }
  });
  with(root, "random_motion", [&](const YAML::Node& v) {
    r.checkKeys(v, "random_motion", {"max_speed", "max_angular_speed", "ball_max_speed", "seed"});
    auto get = [&](const char* key, double def, double hi) {
      return v[key].IsDefined() ? r.number(v[key], std::string("random_motion.") + key, 0, hi) : def;
    };
    const double speed = get("max_speed", 1000, 20000);
    const double turn = get("max_angular_speed", 2, 100);
    const double ball = get("ball_max_speed", 2000, 50000);
    const uint64_t seed = v["seed"].IsDefined() ? r.seed(v["seed"], "random_motion.seed") : s.seed;
    assignRandomMotion(s, speed, turn, ball, s.frames / s.fps, seed);
  });
  return s;
}

}  // namespace

SceneSpec sceneFromYaml(const std::string& text, const std::string& source) {
  const SceneReader reader(source);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(source, "line " + std::to_string(e.mark.line + 1) + ", column " +
                                 std::to_string(e.mark.column + 1) + ": malformed YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw InputError(source, std::string("malformed YAML: ") + e.what());
  }
  try {
    return readScene(reader, root);
  } catch (const InputError&) {
    throw;
  } catch (const YAML::Exception& e) {  // a shape the checks above missed
    throw InputError(source, "line " + std::to_string(e.mark.line + 1) + ", column " +
                                 std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
}

SceneSpec loadScene(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "cannot open the scene file: no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "cannot read the scene file");
  return sceneFromYaml(text.str(), path);
}

std::string presetDirectory() {
  if (const char* env = std::getenv("DV_SCENES_DIR"); env && *env) return env;
  return {};
}

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  const std::string dir = presetDirectory();
  if (dir.empty()) {
    for (int i = 0; i < embeddedSceneCount(); ++i)
      names.push_back(std::filesystem::path(embeddedScenes()[i].name).stem().string());
  } else {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
      if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

SceneSpec presetScene(const std::string& name) {
  const auto names = presetNames();
  const std::string dir = presetDirectory();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    if (names.empty()) list = "none found in " + dir;
    throw InputError("preset", "unknown preset '" + name + "' (known: " + list + ")");
  }
  if (!dir.empty()) return loadScene((std::filesystem::path(dir) / (name + ".yaml")).string());
  for (int i = 0; i < embeddedSceneCount(); ++i)
    if (embeddedScenes()[i].name == name + ".yaml")
      return sceneFromYaml(embeddedScenes()[i].text, "preset " + name);
  throw InputError("preset", "unknown preset '" + name + "'");  // not reached: listed above
}

}  // namespace dv

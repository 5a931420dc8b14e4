// Geometry as YAML, the human-edited form (geometry_io.h): every key
// checked, each problem named with its line and column.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "core/error.h"
#include "geometry/geometry_io.h"
#include "geometry/geometry_io_detail.h"

namespace dv {

using namespace geometry_io_detail;

namespace {

// ---- YAML ----

std::string where(const YAML::Node& n) {
  const auto& mark = n.Mark();
  if (mark.is_null()) return "";
  return "line " + std::to_string(mark.line + 1) + ", column " + std::to_string(mark.column + 1) + ": ";
}

class YamlReader {
 public:
  explicit YamlReader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& what) const {
    throw InputError(source_, where(at) + what);
  }

  void expectMap(const YAML::Node& n, const std::string& what) const {
    if (!n.IsMap()) fail(n, what + " must be a map of key: value");
  }

  // Rejects keys not in `allowed`, so a typo does not silently keep a default.
  void checkKeys(const YAML::Node& map, std::initializer_list<const char*> allowed,
                 const std::string& what) const {
    for (const auto& kv : map) {
      const std::string key = kv.first.as<std::string>();
      bool ok = false;
      for (const char* a : allowed) ok = ok || key == a;
      if (!ok) fail(kv.first, "unknown key '" + key + "' in " + what);
    }
  }

  template <typename T>
  T get(const YAML::Node& map, const char* key, const char* type_name) const {
    const YAML::Node n = map[key];
    if (!n) fail(map, "missing required key '" + std::string(key) + "'");
    return as<T>(n, key, type_name);
  }

  template <typename T>
  T as(const YAML::Node& n, const std::string& key, const char* type_name) const {
    if (!n.IsScalar()) fail(n, "'" + key + "' must be " + type_name);
    try {
      T v = n.as<T>();
      if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(v)) fail(n, "'" + key + "' must be a finite number");
      }
      return v;
    } catch (const YAML::BadConversion&) {
      fail(n, "'" + key + "' must be " + type_name + ", not '" + n.Scalar() + "'");
    }
  }

  FieldMm point(const YAML::Node& n, const std::string& key) const {
    // [x, y] or {x: .., y: ..}
    if (n.IsSequence() && n.size() == 2) return {as<double>(n[0], key, "a number"), as<double>(n[1], key, "a number")};
    if (n.IsMap()) {
      checkKeys(n, {"x", "y"}, "'" + key + "'");
      return {get<double>(n, "x", "a number"), get<double>(n, "y", "a number")};
    }
    fail(n, "'" + key + "' must be [x, y] or {x: .., y: ..}");
  }

  FieldShape shape(const YAML::Node& n) const {
    if (!n.IsScalar()) fail(n, "'type' must be a SSL_FieldShapeType name");
    const auto* desc = dv::ssl::SSL_FieldShapeType_descriptor();
    if (const auto* v = desc->FindValueByName(n.Scalar())) return FieldShape(v->number());
    try {
      const int i = n.as<int>();
      if (desc->FindValueByNumber(i)) return FieldShape(i);
    } catch (const YAML::BadConversion&) {
    }
    fail(n, "'type' " + n.Scalar() + " is not a SSL_FieldShapeType");
  }

  FieldModel field(const YAML::Node& n) const {
    expectMap(n, "'field'");
    for (const auto& kv : n) {
      const std::string key = kv.first.as<std::string>();
      bool ok = key == "division" || key == "field_lines" || key == "field_arcs";
      for (const auto& d : kIntDimensions) ok = ok || key == d.name;
      for (const auto& d : kRealDimensions) ok = ok || key == d.name;
      if (!ok) fail(kv.first, "unknown key '" + key + "' in 'field'");
    }
    FieldModel f;
    if (const YAML::Node d = n["division"]) {
      const std::string div = as<std::string>(d, "division", "A or B");
      if (div == "A" || div == "a") f = FieldModel::divisionA();
      else if (div == "B" || div == "b") f = FieldModel::divisionB();
      else fail(d, "'division' must be A or B, not '" + div + "'");
    } else {
      if (!n["field_length"]) fail(n, "'field' needs 'division' (A or B) or 'field_length'");
      const int length = get<int>(n, "field_length", "an integer (mm)");
      f = presetFor(length);
    }
    bool boundary_goal_line_given = false;
    for (const auto& d : kIntDimensions) {
      if (const YAML::Node v = n[d.name]) {
        f.*d.member = as<int>(v, d.name, "an integer (mm)");
        boundary_goal_line_given = boundary_goal_line_given || d.member == &FieldModel::boundary_width_goal_line;
      }
    }
    if (!n["division"] && !boundary_goal_line_given) f.boundary_width_goal_line = f.boundary_width;
    for (const auto& d : kRealDimensions) {
      if (const YAML::Node v = n[d.name]) f.*d.member = as<double>(v, d.name, "a number (mm)");
    }
    f.generateMarkings();
    const YAML::Node lines = n["field_lines"], arcs = n["field_arcs"];
    if (lines || arcs) {
      f.lines.clear();
      f.arcs.clear();
    }
    if (lines) {
      if (!lines.IsSequence()) fail(lines, "'field_lines' must be a list");
      for (const auto& l : lines) {
        expectMap(l, "a field line");
        checkKeys(l, {"name", "p1", "p2", "thickness", "type"}, "a field line");
        FieldLine line;
        line.name = get<std::string>(l, "name", "a string");
        if (!l["p1"] || !l["p2"]) fail(l, "a field line needs p1 and p2");
        line.p1 = point(l["p1"], "p1");
        line.p2 = point(l["p2"], "p2");
        line.thickness = l["thickness"] ? as<double>(l["thickness"], "thickness", "a number (mm)")
                                        : f.line_thickness;
        if (l["type"]) line.type = shape(l["type"]);
        f.lines.push_back(line);
      }
    }
    if (arcs) {
      if (!arcs.IsSequence()) fail(arcs, "'field_arcs' must be a list");
      for (const auto& a : arcs) {
        expectMap(a, "a field arc");
        checkKeys(a, {"name", "center", "radius", "a1", "a2", "thickness", "type"}, "a field arc");
        FieldArc arc;
        arc.name = get<std::string>(a, "name", "a string");
        if (!a["center"]) fail(a, "missing required key 'center'");
        arc.center = point(a["center"], "center");
        arc.radius = get<double>(a, "radius", "a number (mm)");
        arc.a1 = get<double>(a, "a1", "a number (rad)");
        arc.a2 = get<double>(a, "a2", "a number (rad)");
        arc.thickness = a["thickness"] ? as<double>(a["thickness"], "thickness", "a number (mm)")
                                       : f.line_thickness;
        if (a["type"]) arc.type = shape(a["type"]);
        f.arcs.push_back(arc);
      }
    }
    if (auto problem = fieldProblem(f)) fail(n, "field: " + *problem);
    return f;
  }

  CameraCalibration camera(const YAML::Node& n) const {
    expectMap(n, "a camera");
    checkKeys(n,
              {"camera_id", "focal_length", "principal_point_x", "principal_point_y", "distortion",
               "q0", "q1", "q2", "q3", "tx", "ty", "tz", "derived_camera_world_tx",
               "derived_camera_world_ty", "derived_camera_world_tz", "pixel_image_width",
               "pixel_image_height", "lens"},
              "a camera");
    CameraCalibration c;
    c.camera_id = get<uint32_t>(n, "camera_id", "a non-negative integer");
    const char* num = "a number";
    c.focal_length = get<double>(n, "focal_length", num);
    c.principal_point_x = get<double>(n, "principal_point_x", num);
    c.principal_point_y = get<double>(n, "principal_point_y", num);
    c.distortion = get<double>(n, "distortion", num);
    c.q0 = get<double>(n, "q0", num);
    c.q1 = get<double>(n, "q1", num);
    c.q2 = get<double>(n, "q2", num);
    c.q3 = get<double>(n, "q3", num);
    c.tx = get<double>(n, "tx", num);
    c.ty = get<double>(n, "ty", num);
    c.tz = get<double>(n, "tz", num);
    // derived_camera_world_* are accepted (files written by others) but
    // recomputed from q and t, which are what the model uses.
    for (const char* k : {"derived_camera_world_tx", "derived_camera_world_ty", "derived_camera_world_tz"}) {
      if (n[k]) (void)as<double>(n[k], k, num);
    }
    for (auto [key, member] : {std::pair{"pixel_image_width", &CameraCalibration::image_width},
                               {"pixel_image_height", &CameraCalibration::image_height}}) {
      if (const YAML::Node v = n[key]) {
        c.*member = as<uint32_t>(v, key, "a positive integer");
        if (c.*member == 0) fail(v, "camera " + std::to_string(c.camera_id) + ": '" + key + "' is 0");
      }
    }
    if (const YAML::Node lens = n["lens"]) {
      // dotvision's terms beyond the league's model (LensTerms); each 0 when absent.
      expectMap(lens, "'lens'");
      checkKeys(lens, {"k2", "k3", "p1", "p2"}, "'lens'");
      for (auto [key, member] : {std::pair{"k2", &LensTerms::k2}, {"k3", &LensTerms::k3},
                                 {"p1", &LensTerms::p1}, {"p2", &LensTerms::p2}})
        if (const YAML::Node v = lens[key]) c.lens.*member = as<double>(v, std::string("lens.") + key, num);
    }
    if (auto problem = calibrationProblem(c)) {
      fail(n, "camera " + std::to_string(c.camera_id) + ": implausible calibration: " + *problem);
    }
    return c;
  }

  Geometry geometry(const YAML::Node& root) const {
    if (!root.IsMap()) fail(root, "expected a map with 'field' and 'cameras'");
    checkKeys(root, {"field", "cameras"}, "the top level");
    if (!root["field"]) fail(root, "missing required key 'field'");
    Geometry g;
    g.field = field(root["field"]);
    if (const YAML::Node cams = root["cameras"]) {
      if (!cams.IsSequence() && !cams.IsNull()) fail(cams, "'cameras' must be a list");
      std::set<uint32_t> ids;
      for (const auto& c : cams) {
        g.cameras.push_back(camera(c));
        if (!ids.insert(g.cameras.back().camera_id).second) {
          fail(c, "camera " + std::to_string(g.cameras.back().camera_id) + " is given twice");
        }
      }
    }
    return g;
  }

 private:
  std::string source_;
};

}  // namespace

Geometry geometryFromYaml(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(source, "malformed YAML at line " + std::to_string(e.mark.line + 1) + ", column " +
                                 std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  if (root.IsNull()) throw InputError(source, "the file is empty (expected 'field' and 'cameras')");
  try {
    return YamlReader(source).geometry(root);
  } catch (const YAML::Exception& e) {  // anything the reader did not anticipate
    throw InputError(source, where(root) + e.msg);
  }
}

std::string toYaml(const Geometry& g) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "field" << YAML::Value << YAML::BeginMap;
  const FieldModel& f = g.field;
  for (const auto& d : kIntDimensions) out << YAML::Key << d.name << YAML::Value << f.*d.member;
  for (const auto& d : kRealDimensions) out << YAML::Key << d.name << YAML::Value << shortest(f.*d.member);
  // Lines are written only when they are not the standard ones (which
  // loading regenerates from the dimensions).
  if (!sameMarkings(f)) {
    const auto* types = dv::ssl::SSL_FieldShapeType_descriptor();
    auto typeName = [&](FieldShape s) {
      const auto* v = types->FindValueByNumber(int(s));
      return v ? v->name() : std::to_string(int(s));
    };
    out << YAML::Key << "field_lines" << YAML::Value << YAML::BeginSeq;
    for (const auto& l : f.lines) {
      out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << l.name;
      out << YAML::Key << "p1" << YAML::Value << YAML::Flow << YAML::BeginSeq << shortest(l.p1.x)
          << shortest(l.p1.y) << YAML::EndSeq;
      out << YAML::Key << "p2" << YAML::Value << YAML::Flow << YAML::BeginSeq << shortest(l.p2.x)
          << shortest(l.p2.y) << YAML::EndSeq;
      out << YAML::Key << "thickness" << YAML::Value << shortest(l.thickness);
      out << YAML::Key << "type" << YAML::Value << typeName(l.type) << YAML::EndMap;
    }
    out << YAML::EndSeq;
    out << YAML::Key << "field_arcs" << YAML::Value << YAML::BeginSeq;
    for (const auto& a : f.arcs) {
      out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << a.name;
      out << YAML::Key << "center" << YAML::Value << YAML::Flow << YAML::BeginSeq << shortest(a.center.x)
          << shortest(a.center.y) << YAML::EndSeq;
      out << YAML::Key << "radius" << YAML::Value << shortest(a.radius);
      out << YAML::Key << "a1" << YAML::Value << shortest(a.a1);
      out << YAML::Key << "a2" << YAML::Value << shortest(a.a2);
      out << YAML::Key << "thickness" << YAML::Value << shortest(a.thickness);
      out << YAML::Key << "type" << YAML::Value << typeName(a.type) << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
  if (!g.cameras.empty()) {
    out << YAML::Key << "cameras" << YAML::Value << YAML::BeginSeq;
    for (const auto& c : g.cameras) {
      out << YAML::BeginMap;
      out << YAML::Key << "camera_id" << YAML::Value << c.camera_id;
      auto real = [&](const char* k, double v) { out << YAML::Key << k << YAML::Value << shortest(v); };
      real("focal_length", c.focal_length);
      real("principal_point_x", c.principal_point_x);
      real("principal_point_y", c.principal_point_y);
      real("distortion", c.distortion);
      real("q0", c.q0);
      real("q1", c.q1);
      real("q2", c.q2);
      real("q3", c.q3);
      real("tx", c.tx);
      real("ty", c.ty);
      real("tz", c.tz);
      if (c.image_width > 0) out << YAML::Key << "pixel_image_width" << YAML::Value << c.image_width;
      if (c.image_height > 0) out << YAML::Key << "pixel_image_height" << YAML::Value << c.image_height;
      if (c.lens.any()) {
        out << YAML::Key << "lens" << YAML::Value << YAML::Flow << YAML::BeginMap;
        real("k2", c.lens.k2);
        real("k3", c.lens.k3);
        real("p1", c.lens.p1);
        real("p2", c.lens.p2);
        out << YAML::EndMap;
      }
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}


}  // namespace dv

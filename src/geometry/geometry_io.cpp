#include "geometry/geometry_io.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/error.h"
#include "geometry/calibration/league_fit.h"
#include "geometry/proto_json.h"

namespace dv {

const CameraCalibration* Geometry::camera(uint32_t id) const {
  for (const auto& c : cameras) {
    if (c.camera_id == id) return &c;
  }
  return nullptr;
}

namespace {

// ---- the field's scalar dimensions, by their proto names ----

struct IntDimension {
  const char* name;
  int FieldModel::*member;
};
constexpr IntDimension kIntDimensions[] = {
    {"field_length", &FieldModel::field_length},
    {"field_width", &FieldModel::field_width},
    {"goal_width", &FieldModel::goal_width},
    {"goal_depth", &FieldModel::goal_depth},
    {"boundary_width", &FieldModel::boundary_width},
    {"boundary_width_goal_line", &FieldModel::boundary_width_goal_line},
    {"penalty_area_depth", &FieldModel::penalty_area_depth},
    {"penalty_area_width", &FieldModel::penalty_area_width},
    {"center_circle_radius", &FieldModel::center_circle_radius},
    {"line_thickness", &FieldModel::line_thickness},
    {"goal_center_to_penalty_mark", &FieldModel::goal_center_to_penalty_mark},
    {"goal_height", &FieldModel::goal_height},
    {"goal_substitution_area_width", &FieldModel::goal_substitution_area_width},
};
struct RealDimension {
  const char* name;
  double FieldModel::*member;
};
constexpr RealDimension kRealDimensions[] = {
    {"ball_radius", &FieldModel::ball_radius},
    {"max_robot_radius", &FieldModel::max_robot_radius},
};

// Division A is 12000 mm long, B 9000: a field takes its missing optional
// dimensions from the preset nearer its length.
FieldModel presetFor(int field_length) {
  return field_length >= 10500 ? FieldModel::divisionA() : FieldModel::divisionB();
}

bool sameMarkings(const FieldModel& f) {
  FieldModel generated = f;
  generated.generateMarkings();
  auto same = [](FieldMm a, FieldMm b) { return a.x == b.x && a.y == b.y; };
  if (generated.lines.size() != f.lines.size() || generated.arcs.size() != f.arcs.size()) return false;
  for (size_t i = 0; i < f.lines.size(); ++i) {
    const auto &a = f.lines[i], &b = generated.lines[i];
    if (a.name != b.name || !same(a.p1, b.p1) || !same(a.p2, b.p2) || a.thickness != b.thickness ||
        a.type != b.type)
      return false;
  }
  for (size_t i = 0; i < f.arcs.size(); ++i) {
    const auto &a = f.arcs[i], &b = generated.arcs[i];
    if (a.name != b.name || !same(a.center, b.center) || a.radius != b.radius || a.a1 != b.a1 ||
        a.a2 != b.a2 || a.thickness != b.thickness || a.type != b.type)
      return false;
  }
  return true;
}

std::string lowerExtension(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw InputError(path, "read error");
  return s.str();
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(path, std::string("cannot write: ") + std::strerror(errno));
  out << text;
  out.flush();
  if (!out) throw InputError(path, "write error");
}

// Shortest text that reads back as the same double (human-friendly YAML).
std::string shortest(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string fmt(double v) { return shortest(v); }

bool finite(double v) { return std::isfinite(v); }

}  // namespace

// ---- proto conversion ----

dv::ssl::SSL_GeometryFieldSize toProto(const FieldModel& f) {
  dv::ssl::SSL_GeometryFieldSize m;
  const auto* refl = m.GetReflection();
  const auto* desc = m.GetDescriptor();
  for (const auto& d : kIntDimensions) refl->SetInt32(&m, desc->FindFieldByName(d.name), f.*d.member);
  for (const auto& d : kRealDimensions) refl->SetFloat(&m, desc->FindFieldByName(d.name), float(f.*d.member));
  for (const auto& l : f.lines) {
    auto* p = m.add_field_lines();
    p->set_name(l.name);
    p->mutable_p1()->set_x(float(l.p1.x));
    p->mutable_p1()->set_y(float(l.p1.y));
    p->mutable_p2()->set_x(float(l.p2.x));
    p->mutable_p2()->set_y(float(l.p2.y));
    p->set_thickness(float(l.thickness));
    p->set_type(dv::ssl::SSL_FieldShapeType(l.type));
  }
  for (const auto& a : f.arcs) {
    auto* p = m.add_field_arcs();
    p->set_name(a.name);
    p->mutable_center()->set_x(float(a.center.x));
    p->mutable_center()->set_y(float(a.center.y));
    p->set_radius(float(a.radius));
    p->set_a1(float(a.a1));
    p->set_a2(float(a.a2));
    p->set_thickness(float(a.thickness));
    p->set_type(dv::ssl::SSL_FieldShapeType(a.type));
  }
  return m;
}

FieldModel fieldFromProto(const dv::ssl::SSL_GeometryFieldSize& m) {
  FieldModel f = presetFor(m.field_length());
  // Older senders have one boundary for all sides.
  f.boundary_width_goal_line = m.boundary_width();
  const auto* refl = m.GetReflection();
  const auto* desc = m.GetDescriptor();
  for (const auto& d : kIntDimensions) {
    const auto* fd = desc->FindFieldByName(d.name);
    if (refl->HasField(m, fd)) f.*d.member = refl->GetInt32(m, fd);
  }
  for (const auto& d : kRealDimensions) {
    const auto* fd = desc->FindFieldByName(d.name);
    if (refl->HasField(m, fd)) f.*d.member = refl->GetFloat(m, fd);
  }
  f.lines.clear();
  f.arcs.clear();
  if (m.field_lines_size() == 0 && m.field_arcs_size() == 0) {
    f.generateMarkings();
    return f;
  }
  for (const auto& p : m.field_lines()) {
    f.lines.push_back({p.name(), {p.p1().x(), p.p1().y()}, {p.p2().x(), p.p2().y()}, p.thickness(),
                       FieldShape(p.type())});
  }
  for (const auto& p : m.field_arcs()) {
    f.arcs.push_back({p.name(), {p.center().x(), p.center().y()}, p.radius(), p.a1(), p.a2(),
                      p.thickness(), FieldShape(p.type())});
  }
  return f;
}

dv::ssl::SSL_GeometryCameraCalibration toProto(const CameraCalibration& calibration) {
  // Packets carry the league's model: a lens with more terms is sent as the
  // league model's best fit to it.
  const CameraCalibration c = calibration.lens.any() ? leagueFit(calibration).calibration : calibration;
  dv::ssl::SSL_GeometryCameraCalibration m;
  m.set_camera_id(c.camera_id);
  m.set_focal_length(float(c.focal_length));
  m.set_principal_point_x(float(c.principal_point_x));
  m.set_principal_point_y(float(c.principal_point_y));
  m.set_distortion(float(c.distortion));
  m.set_q0(float(c.q0));
  m.set_q1(float(c.q1));
  m.set_q2(float(c.q2));
  m.set_q3(float(c.q3));
  m.set_tx(float(c.tx));
  m.set_ty(float(c.ty));
  m.set_tz(float(c.tz));
  // A zero quaternion has no position; leave the derived fields out then.
  if (c.q0 * c.q0 + c.q1 * c.q1 + c.q2 * c.q2 + c.q3 * c.q3 > 0) {
    const Eigen::Vector3d pos = CameraModel(c).position();
    if (pos.allFinite()) {
      m.set_derived_camera_world_tx(float(pos.x()));
      m.set_derived_camera_world_ty(float(pos.y()));
      m.set_derived_camera_world_tz(float(pos.z()));
    }
  }
  if (c.image_width > 0) m.set_pixel_image_width(c.image_width);
  if (c.image_height > 0) m.set_pixel_image_height(c.image_height);
  return m;
}

CameraCalibration calibrationFromProto(const dv::ssl::SSL_GeometryCameraCalibration& m) {
  CameraCalibration c;
  c.camera_id = m.camera_id();
  c.focal_length = m.focal_length();
  c.principal_point_x = m.principal_point_x();
  c.principal_point_y = m.principal_point_y();
  c.distortion = m.distortion();
  c.q0 = m.q0(), c.q1 = m.q1(), c.q2 = m.q2(), c.q3 = m.q3();
  c.tx = m.tx(), c.ty = m.ty(), c.tz = m.tz();
  c.image_width = m.has_pixel_image_width() ? m.pixel_image_width() : 0;
  c.image_height = m.has_pixel_image_height() ? m.pixel_image_height() : 0;
  return c;
}

dv::ssl::SSL_GeometryData toProto(const Geometry& g) {
  dv::ssl::SSL_GeometryData m;
  *m.mutable_field() = toProto(g.field);
  for (const auto& c : g.cameras) *m.add_calib() = toProto(c);
  return m;
}

Geometry withWirePrecision(const Geometry& g, const std::string& source) {
  Geometry out = geometryFromProto(toProto(g), source);
  for (const auto& c : g.cameras) {
    if (!c.lens.any()) continue;
    const auto f = [](double v) { return double(float(v)); };
    CameraCalibration r = c;
    for (double* v : {&r.focal_length, &r.principal_point_x, &r.principal_point_y, &r.distortion, &r.q0, &r.q1,
                      &r.q2, &r.q3, &r.tx, &r.ty, &r.tz, &r.lens.k2, &r.lens.k3, &r.lens.p1, &r.lens.p2})
      *v = f(*v);
    for (auto& o : out.cameras)
      if (o.camera_id == c.camera_id) o = r;
  }
  return out;
}

// ---- validation ----

std::optional<std::string> calibrationProblem(const CameraCalibration& c) {
  const double values[] = {c.focal_length, c.principal_point_x, c.principal_point_y, c.distortion,
                           c.q0, c.q1, c.q2, c.q3, c.tx, c.ty, c.tz,
                           c.lens.k2, c.lens.k3, c.lens.p1, c.lens.p2};
  for (double v : values) {
    if (!finite(v)) return "a parameter is NaN or infinite";
  }
  if (!(c.focal_length > 0)) return "focal_length " + fmt(c.focal_length) + " px is not positive";
  const double n2 = c.q0 * c.q0 + c.q1 * c.q1 + c.q2 * c.q2 + c.q3 * c.q3;
  if (n2 < 1e-6) return "the rotation quaternion (q0..q3) is zero";
  // Senders normalise; a length off by more than float rounding is damage
  // (a flipped bit), not a rotation.
  if (std::abs(std::sqrt(n2) - 1) > kQuaternionLengthTolerance) {
    return "the rotation quaternion (q0..q3) has length " + fmt(std::sqrt(n2)) + ", not 1";
  }
  const CameraModel model(c);
  const Eigen::Vector3d& pos = model.position();
  if (!pos.allFinite()) return "the camera position is not finite";
  if (!(pos.z() > 0)) {
    return "the camera center is at z = " + fmt(pos.z()) + " mm, at or below the field";
  }
  // The optical axis in field coordinates; a camera that looks at or above
  // the horizon cannot see the field.
  const double axis_z = model.rotation().row(2).z();
  if (!(axis_z < 0)) return "the optical axis does not point down at the field";
  if (c.image_width > 0 && c.image_height > 0 &&
      (c.principal_point_x < 0 || c.principal_point_x > c.image_width || c.principal_point_y < 0 ||
       c.principal_point_y > c.image_height)) {
    return "the principal point (" + fmt(c.principal_point_x) + ", " + fmt(c.principal_point_y) +
           ") lies outside the " + std::to_string(c.image_width) + "x" +
           std::to_string(c.image_height) + " image";
  }
  return std::nullopt;
}

std::optional<std::string> calibrationProblem(const dv::ssl::SSL_GeometryCameraCalibration& m) {
  // 0 in CameraCalibration means "not given"; a sender that gives 0 is wrong.
  if (m.has_pixel_image_width() && m.pixel_image_width() == 0) return "pixel_image_width is 0";
  if (m.has_pixel_image_height() && m.pixel_image_height() == 0) return "pixel_image_height is 0";
  return calibrationProblem(calibrationFromProto(m));
}

void validateCalibration(const CameraCalibration& c, const std::string& source) {
  if (auto problem = calibrationProblem(c)) {
    throw InputError(source, "camera " + std::to_string(c.camera_id) + ": implausible calibration: " +
                                 *problem);
  }
}

std::optional<std::string> fieldProblem(const FieldModel& f) {
  // Lengths are millimetres; a field under a metre was most likely given in
  // metres, one over 100 m is a typo.
  for (auto [name, v] : {std::pair{"field_length", f.field_length}, {"field_width", f.field_width}}) {
    if (v < 1000 || v > 100000) {
      return std::string(name) + " " + std::to_string(v) + " mm is outside 1000..100000 mm";
    }
  }
  for (const auto& d : kIntDimensions) {
    const int v = f.*d.member;
    const bool may_be_zero = d.member == &FieldModel::boundary_width ||
                             d.member == &FieldModel::boundary_width_goal_line ||
                             d.member == &FieldModel::goal_substitution_area_width;
    if (v < 0 || (v == 0 && !may_be_zero)) {
      return std::string(d.name) + " " + std::to_string(v) + " mm is not positive";
    }
  }
  for (const auto& d : kRealDimensions) {
    const double v = f.*d.member;
    if (!finite(v) || v <= 0) return std::string(d.name) + " " + fmt(v) + " mm is not positive";
  }
  if (f.goal_width > f.field_width) return "goal_width is larger than field_width";
  if (f.penalty_area_width > f.field_width) return "penalty_area_width is larger than field_width";
  if (2 * f.penalty_area_depth > f.field_length) {
    return "penalty_area_depth is more than half of field_length";
  }
  if (2 * f.center_circle_radius > std::min(f.field_length, f.field_width)) {
    return "the center circle does not fit in the field";
  }
  // Markings lie on the field with its boundary; one a field length or more
  // away from the centre is a damaged number.
  const double reach = f.field_length + f.field_width;
  auto onField = [&](FieldMm p) { return std::abs(p.x) <= reach && std::abs(p.y) <= reach; };
  for (const auto& l : f.lines) {
    if (!finite(l.p1.x) || !finite(l.p1.y) || !finite(l.p2.x) || !finite(l.p2.y) ||
        !finite(l.thickness) || l.thickness <= 0) {
      return "field line '" + l.name + "' has a non-finite point or a thickness <= 0";
    }
    if (!onField(l.p1) || !onField(l.p2) || l.thickness > reach) {
      return "field line '" + l.name + "' lies beyond the field (a coordinate or the thickness is over " +
             fmt(reach) + " mm)";
    }
  }
  for (const auto& a : f.arcs) {
    if (!finite(a.center.x) || !finite(a.center.y) || !finite(a.radius) || !finite(a.a1) ||
        !finite(a.a2) || !finite(a.thickness) || a.radius <= 0 || a.thickness <= 0) {
      return "field arc '" + a.name + "' has a non-finite value, or a radius or thickness <= 0";
    }
    if (!onField(a.center) || a.radius > reach || a.thickness > reach) {
      return "field arc '" + a.name + "' lies beyond the field (the centre, radius or thickness is over " +
             fmt(reach) + " mm)";
    }
  }
  return std::nullopt;
}

void validateField(const FieldModel& f, const std::string& source) {
  if (auto problem = fieldProblem(f)) throw InputError(source, "field: " + *problem);
}

namespace {

void validateGeometry(const Geometry& g, const std::string& source) {
  validateField(g.field, source);
  std::set<uint32_t> ids;
  for (const auto& c : g.cameras) {
    validateCalibration(c, source);
    if (!ids.insert(c.camera_id).second) {
      throw InputError(source, "camera " + std::to_string(c.camera_id) + " is given twice");
    }
  }
}

}  // namespace

Geometry geometryFromProto(const dv::ssl::SSL_GeometryData& m, const std::string& source) {
  if (!m.IsInitialized()) {
    throw InputError(source, "SSL_GeometryData lacks required fields: " + m.InitializationErrorString());
  }
  Geometry g;
  g.field = fieldFromProto(m.field());
  for (const auto& c : m.calib()) {
    if (auto problem = calibrationProblem(c)) {
      throw InputError(source, "camera " + std::to_string(c.camera_id()) + ": implausible calibration: " +
                                   *problem);
    }
    g.cameras.push_back(calibrationFromProto(c));
  }
  validateGeometry(g, source);
  return g;
}

// ---- JSON ----

namespace {

// Protobuf's JSON parser does not say where a syntax error is; nlohmann does,
// so the text is checked with it first to report line and column.
// It also checks the outer shape, where protobuf's messages mislead (an array
// in place of "field" is reported as "missing field field").
// "line L, column C" of byte `byte` (0-based) in `text`.
std::string lineAndColumn(const std::string& text, size_t byte) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < std::min(text.size(), byte); ++i) {
    if (text[i] == '\n') ++line, column = 1;
    else ++column;
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann reports some errors without a place (a number that overflows a
// double: out_of_range.406); a SAX pass that records where the first error
// starts finds it.
struct FirstErrorByte : nlohmann::json_sax<nlohmann::json> {
  size_t byte = 0;
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t end, const std::string& token, const nlohmann::detail::exception&) override {
    byte = end >= token.size() ? end - token.size() : 0;  // `end` is just past the token
    return false;
  }
};

// dotvision's key beside SSL_GeometryData in .json files: the cameras whose
// lens has terms beyond the league's model, in full (the "calib" entries hold
// their league fits, for other readers).
constexpr const char* kLensKey = "dotvisionLenses";
constexpr const char* kLensCameraKeys[] = {"cameraId", "focalLength", "principalPointX", "principalPointY",
                                           "distortion", "q0", "q1", "q2", "q3", "tx", "ty", "tz",
                                           "k2", "k3", "p1", "p2"};

nlohmann::json lensCameraJson(const CameraCalibration& c) {
  const double v[] = {c.focal_length, c.principal_point_x, c.principal_point_y, c.distortion, c.q0, c.q1,
                      c.q2, c.q3, c.tx, c.ty, c.tz, c.lens.k2, c.lens.k3, c.lens.p1, c.lens.p2};
  nlohmann::json j = nlohmann::json::object();
  j[kLensCameraKeys[0]] = c.camera_id;
  for (size_t i = 0; i < std::size(v); ++i) j[kLensCameraKeys[i + 1]] = v[i];
  return j;
}

// Replaces the league fits in `g` by the full calibrations of `lenses`.
void applyLensCameras(const nlohmann::json& lenses, Geometry& g, const std::string& source) {
  for (size_t i = 0; i < lenses.size(); ++i) {
    const std::string at = std::string(kLensKey) + "[" + std::to_string(i) + "]";
    const nlohmann::json& e = lenses[i];
    if (!e.is_object()) throw InputError(source, at + " must be an object");
    for (auto it = e.begin(); it != e.end(); ++it) {
      const std::string& key = it.key();
      if (std::find_if(std::begin(kLensCameraKeys), std::end(kLensCameraKeys),
                       [&](const char* k) { return key == k; }) == std::end(kLensCameraKeys))
        throw InputError(source, at + ": unknown key \"" + key + "\"");
      if (!it.value().is_number()) throw InputError(source, at + ": \"" + key + "\" must be a number");
    }
    for (const char* k : kLensCameraKeys)
      if (!e.contains(k)) throw InputError(source, at + " lacks \"" + std::string(k) + "\"");
    const nlohmann::json& id = e["cameraId"];
    if (!id.is_number_unsigned() || id.get<uint64_t>() > UINT32_MAX)
      throw InputError(source, at + ": \"cameraId\" must be a non-negative integer");
    CameraCalibration* c = nullptr;
    for (auto& cam : g.cameras)
      if (cam.camera_id == id.get<uint32_t>()) c = &cam;
    if (!c) throw InputError(source, at + ": camera " + std::to_string(id.get<uint32_t>()) + " is not in \"calib\"");
    double v[15];
    for (size_t k = 0; k < 15; ++k) v[k] = e[kLensCameraKeys[k + 1]].get<double>();
    c->focal_length = v[0], c->principal_point_x = v[1], c->principal_point_y = v[2], c->distortion = v[3];
    c->q0 = v[4], c->q1 = v[5], c->q2 = v[6], c->q3 = v[7], c->tx = v[8], c->ty = v[9], c->tz = v[10];
    c->lens = {v[11], v[12], v[13], v[14]};
    if (auto problem = calibrationProblem(*c))
      throw InputError(source, at + ": camera " + std::to_string(c->camera_id) + ": implausible calibration: " + *problem);
  }
}

nlohmann::json checkJsonSyntaxAndShape(const std::string& text, const std::string& source) {
  nlohmann::json parsed;
  try {
    parsed = nlohmann::json::parse(text);
  } catch (const nlohmann::json::out_of_range& e) {
    FirstErrorByte place;
    nlohmann::json::sax_parse(text, &place);
    std::string what = e.what();
    // "[json.exception.out_of_range.406] number overflow parsing '1e400'"
    if (auto bracket = what.find("] "); bracket != std::string::npos) what = what.substr(bracket + 2);
    throw InputError(source, "malformed JSON at " + lineAndColumn(text, place.byte) + ": " + what);
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();
    // "[json.exception.parse_error.101] parse error at line 1, column 5: syntax error ..."
    if (auto colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
    throw InputError(source, "malformed JSON at " + lineAndColumn(text, e.byte > 0 ? e.byte - 1 : 0) +
                                 ": " + what);
  }
  if (!parsed.is_object()) throw InputError(source, "expected a JSON object (SSL_GeometryData)");
  for (const auto& [key, value] : parsed.items()) {
    if (key == "field") {
      if (!value.is_object()) throw InputError(source, "\"field\" must be an object (SSL_GeometryFieldSize)");
    } else if (key == "calib") {
      if (!value.is_array()) throw InputError(source, "\"calib\" must be a list of camera calibrations");
      for (size_t i = 0; i < value.size(); ++i) {
        if (!value[i].is_object()) {
          throw InputError(source, "calib[" + std::to_string(i) + "] must be an object (SSL_GeometryCameraCalibration)");
        }
      }
    } else if (key == kLensKey) {
      if (!value.is_array()) throw InputError(source, "\"" + std::string(kLensKey) + "\" must be a list of cameras");
    } else if (key != "models") {
      throw InputError(source, "unknown field \"" + key + "\" in SSL_GeometryData (expected field, calib, models, " +
                                   kLensKey + ")");
    }
  }
  if (!parsed.contains("field")) throw InputError(source, "SSL_GeometryData lacks the required \"field\"");
  return parsed;
}

}  // namespace

Geometry geometryFromJson(const std::string& text, const std::string& source) {
  nlohmann::json parsed = checkJsonSyntaxAndShape(text, source);
  dv::ssl::SSL_GeometryData m;
  if (!parsed.contains(kLensKey)) {
    parseCanonicalJson(text, m, source);
    return geometryFromProto(m, source);
  }
  const nlohmann::json lenses = parsed[kLensKey];
  parsed.erase(kLensKey);
  parseCanonicalJson(parsed.dump(), m, source);
  Geometry g = geometryFromProto(m, source);
  applyLensCameras(lenses, g, source);
  return g;
}

std::string toJson(const Geometry& g) {
  std::string text = toCanonicalJson(toProto(g));
  nlohmann::json lenses = nlohmann::json::array();
  for (const auto& c : g.cameras)
    if (c.lens.any()) lenses.push_back(lensCameraJson(c));
  if (!lenses.empty() && !text.empty() && text.back() == '}') {
    text.pop_back();
    text += ",\"" + std::string(kLensKey) + "\":" + lenses.dump() + "}";
  }
  return text;
}

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

// ---- files ----

Geometry loadGeometry(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext != "json" && ext != "yaml" && ext != "yml") {
    throw InputError(path, "unknown geometry file type '." + ext + "' (expected .json, .yaml or .yml)");
  }
  const std::string text = readFile(path);
  if (ext == "json") return geometryFromJson(text, path);
  return geometryFromYaml(text, path);
}

void saveGeometry(const Geometry& g, const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == "json") {
    writeFile(path, toJson(g) + "\n");
  } else if (ext == "yaml" || ext == "yml") {
    writeFile(path, toYaml(g));
  } else {
    throw InputError(path, "unknown geometry file type '." + ext + "' (expected .json, .yaml or .yml)");
  }
}

}  // namespace dv

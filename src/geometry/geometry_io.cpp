#include "geometry/geometry_io.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "geometry/calibration/league_fit.h"
#include "geometry/geometry_io_detail.h"

namespace dv {

const CameraCalibration* Geometry::camera(uint32_t id) const {
  for (const auto& c : cameras) {
    if (c.camera_id == id) return &c;
  }
  return nullptr;
}

namespace geometry_io_detail {

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

std::string shortest(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace geometry_io_detail

using namespace geometry_io_detail;

namespace {

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

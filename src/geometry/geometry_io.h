#pragma once
// The field and camera calibrations as one value (SSL_GeometryData), with its
// two on-disk forms:
//  - .json: SSL_GeometryData in protobuf canonical JSON (what SSL-Vision and
//    dotvision publish, byte for byte the same content);
//  - .yaml / .yml: a form for people to edit, see config/fields/example.yaml.
// Everything read from outside is validated here, so the rest of dotvision
// can trust a Geometry.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dotvision/ssl_geometry.pb.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"

namespace dv {

struct Geometry {
  FieldModel field;
  std::vector<CameraCalibration> cameras;

  // The calibration of camera `id`, nullptr if absent.
  const CameraCalibration* camera(uint32_t id) const;
};

// Reads .json (canonical JSON of SSL_GeometryData) or .yaml/.yml. Throws
// InputError(path, place + what) for unreadable, malformed or implausible
// content.
Geometry loadGeometry(const std::string& path);
// Writes by extension (.json: one line of canonical JSON; .yaml/.yml).
// Throws InputError(path, ...) when the file cannot be written or the
// extension is unknown.
void saveGeometry(const Geometry& g, const std::string& path);

// The YAML form as a string, and back. `source` names the text in errors.
std::string toYaml(const Geometry& g);
Geometry geometryFromYaml(const std::string& text, const std::string& source);
// The text of a .json geometry file; throws InputError naming `source`.
// Cameras with lens terms (LensTerms) are written as their league fit in
// "calib" (what other readers and packets see) and in full under the
// top-level key "dotvisionLenses", which this reads back.
Geometry geometryFromJson(const std::string& text, const std::string& source);
std::string toJson(const Geometry& g);

dv::ssl::SSL_GeometryData toProto(const Geometry& g);
// What processors use: `g` through the wire's single-precision floats, so
// replays match; a camera with lens terms keeps its own lens (rounded the
// same way) where the wire would carry its league fit.
Geometry withWirePrecision(const Geometry& g, const std::string& source);
dv::ssl::SSL_GeometryFieldSize toProto(const FieldModel& f);
// Fills derived_camera_world_* from CameraModel::position(), and
// pixel_image_width/height when known (non-zero). A calibration with lens
// terms is sent as the league model's best fit to it (leagueFit).
dv::ssl::SSL_GeometryCameraCalibration toProto(const CameraCalibration& c);

// Validates the field and every calibration; generates the markings when the
// message has none (SSL-Vision omits them until its "Update" is pressed).
// Throws InputError(source, ...).
Geometry geometryFromProto(const dv::ssl::SSL_GeometryData& m, const std::string& source);
// Does not validate (see validateField). Missing optional dimensions are taken
// from the division preset nearest in size; no lines -> generated markings.
FieldModel fieldFromProto(const dv::ssl::SSL_GeometryFieldSize& m);
CameraCalibration calibrationFromProto(const dv::ssl::SSL_GeometryCameraCalibration& m);

// |q| may differ from 1 by this much (float rounding of a normalised q).
inline constexpr double kQuaternionLengthTolerance = 1e-3;

// What makes a calibration implausible (focal <= 0, NaN/inf, a quaternion
// that is zero or not of unit length, camera at or below the field), or
// nullopt when it is usable. Does not allocate on success, so receivers can
// call it on every packet.
std::optional<std::string> calibrationProblem(const CameraCalibration& c);
// The same for a calibration as sent, where an image size given as 0 is
// also implausible (CameraCalibration takes 0 as "not given").
std::optional<std::string> calibrationProblem(const dv::ssl::SSL_GeometryCameraCalibration& m);
// Throws InputError(source, "camera N: " + problem) when implausible.
void validateCalibration(const CameraCalibration& c, const std::string& source);

// What makes a field unusable (a dimension <= 0 or not finite, areas that do
// not fit in the field, a line with a non-finite point or one beyond the
// field), or nullopt.
std::optional<std::string> fieldProblem(const FieldModel& f);
void validateField(const FieldModel& f, const std::string& source);

}  // namespace dv

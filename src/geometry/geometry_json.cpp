// Geometry as SSL_GeometryData in protobuf's canonical JSON, with the full
// lens calibrations beside the league fits (geometry_io.h).
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "geometry/calibration/league_fit.h"
#include "geometry/geometry_io.h"
#include "geometry/proto_json.h"

namespace dv {

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

}  // namespace dv

// Geometry files: the league's line tables, JSON and YAML round trips, the
// shipped field files, and one clear InputError for each kind of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "core/error.h"
#include "temp_dir.h"
#include "geometry/geometry_io.h"
#include "geometry/proto_json.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

// A file in a fresh per-process folder; removed with the folder at exit.
std::string tempPath(const std::string& name) {
  static const TempDir dir("dv_geometry_io_test");
  return dir.file(name);
}

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = tempPath(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The message of the InputError `f` throws; fails the test if it throws
// nothing or something else.
std::string inputErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected InputError, nothing was thrown";
  return "";
}

CameraCalibration overheadCamera(uint32_t id, double x, double y) {
  Eigen::Matrix3d down;  // image right = field +x, image down = field -y
  down << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  auto c = CameraCalibration::fromPose(id, 1234.5, 1224.25, 1023.75, 0.071, down, {x, y, 4123.4});
  c.image_width = 2448;
  c.image_height = 2048;
  return c;
}

CameraCalibration tiltedCamera(uint32_t id) {
  CameraCalibration c;
  c.camera_id = id;
  c.focal_length = 1100;
  c.principal_point_x = 1224;
  c.principal_point_y = 1024;
  c.distortion = 0.12;
  c.q0 = -0.703233, c.q1 = -0.703233, c.q2 = -0.073913, c.q3 = 0.073913;
  c.tx = 1000, c.ty = -3766.09, c.tz = 3288.855;
  return c;  // image size unknown
}

Geometry twoCameraGeometry(FieldModel field) {
  Geometry g;
  g.field = std::move(field);
  g.cameras = {overheadCamera(0, -2250, 0), tiltedCamera(1)};
  return g;
}

void expectSameField(const FieldModel& a, const FieldModel& b) {
  EXPECT_EQ(a.field_length, b.field_length);
  EXPECT_EQ(a.field_width, b.field_width);
  EXPECT_EQ(a.goal_width, b.goal_width);
  EXPECT_EQ(a.goal_depth, b.goal_depth);
  EXPECT_EQ(a.boundary_width, b.boundary_width);
  EXPECT_EQ(a.boundary_width_goal_line, b.boundary_width_goal_line);
  EXPECT_EQ(a.penalty_area_depth, b.penalty_area_depth);
  EXPECT_EQ(a.penalty_area_width, b.penalty_area_width);
  EXPECT_EQ(a.center_circle_radius, b.center_circle_radius);
  EXPECT_EQ(a.line_thickness, b.line_thickness);
  EXPECT_EQ(a.goal_center_to_penalty_mark, b.goal_center_to_penalty_mark);
  EXPECT_EQ(a.goal_height, b.goal_height);
  EXPECT_EQ(a.goal_substitution_area_width, b.goal_substitution_area_width);
  EXPECT_FLOAT_EQ(a.ball_radius, b.ball_radius);
  EXPECT_FLOAT_EQ(a.max_robot_radius, b.max_robot_radius);
  ASSERT_EQ(a.lines.size(), b.lines.size());
  for (size_t i = 0; i < a.lines.size(); ++i) {
    SCOPED_TRACE(a.lines[i].name);
    EXPECT_EQ(a.lines[i].name, b.lines[i].name);
    EXPECT_EQ(a.lines[i].type, b.lines[i].type);
    EXPECT_FLOAT_EQ(a.lines[i].p1.x, b.lines[i].p1.x);
    EXPECT_FLOAT_EQ(a.lines[i].p1.y, b.lines[i].p1.y);
    EXPECT_FLOAT_EQ(a.lines[i].p2.x, b.lines[i].p2.x);
    EXPECT_FLOAT_EQ(a.lines[i].p2.y, b.lines[i].p2.y);
    EXPECT_FLOAT_EQ(a.lines[i].thickness, b.lines[i].thickness);
  }
  ASSERT_EQ(a.arcs.size(), b.arcs.size());
  for (size_t i = 0; i < a.arcs.size(); ++i) {
    EXPECT_EQ(a.arcs[i].name, b.arcs[i].name);
    EXPECT_EQ(a.arcs[i].type, b.arcs[i].type);
    EXPECT_FLOAT_EQ(a.arcs[i].center.x, b.arcs[i].center.x);
    EXPECT_FLOAT_EQ(a.arcs[i].center.y, b.arcs[i].center.y);
    EXPECT_FLOAT_EQ(a.arcs[i].radius, b.arcs[i].radius);
    EXPECT_FLOAT_EQ(a.arcs[i].a1, b.arcs[i].a1);
    EXPECT_FLOAT_EQ(a.arcs[i].a2, b.arcs[i].a2);
    EXPECT_FLOAT_EQ(a.arcs[i].thickness, b.arcs[i].thickness);
  }
}

void expectSameCamera(const CameraCalibration& a, const CameraCalibration& b) {
  SCOPED_TRACE("camera " + std::to_string(a.camera_id));
  EXPECT_EQ(a.camera_id, b.camera_id);
  EXPECT_FLOAT_EQ(a.focal_length, b.focal_length);
  EXPECT_FLOAT_EQ(a.principal_point_x, b.principal_point_x);
  EXPECT_FLOAT_EQ(a.principal_point_y, b.principal_point_y);
  EXPECT_FLOAT_EQ(a.distortion, b.distortion);
  EXPECT_FLOAT_EQ(a.q0, b.q0);
  EXPECT_FLOAT_EQ(a.q1, b.q1);
  EXPECT_FLOAT_EQ(a.q2, b.q2);
  EXPECT_FLOAT_EQ(a.q3, b.q3);
  EXPECT_FLOAT_EQ(a.tx, b.tx);
  EXPECT_FLOAT_EQ(a.ty, b.ty);
  EXPECT_FLOAT_EQ(a.tz, b.tz);
  EXPECT_EQ(a.image_width, b.image_width);
  EXPECT_EQ(a.image_height, b.image_height);
}

void expectSameGeometry(const Geometry& a, const Geometry& b) {
  expectSameField(a.field, b.field);
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (size_t i = 0; i < a.cameras.size(); ++i) expectSameCamera(a.cameras[i], b.cameras[i]);
}

void expectLine(const FieldModel& f, size_t index, const char* name, FieldMm p1, FieldMm p2) {
  ASSERT_LT(index, f.lines.size());
  const FieldLine& l = f.lines[index];
  EXPECT_EQ(l.name, name);
  EXPECT_EQ(l.p1.x, p1.x) << name;
  EXPECT_EQ(l.p1.y, p1.y) << name;
  EXPECT_EQ(l.p2.x, p2.x) << name;
  EXPECT_EQ(l.p2.y, p2.y) << name;
  EXPECT_EQ(l.thickness, 10) << name;
}

// ---- the league's line tables (ssl-facts §4.2) ----

TEST(GeometryIo, DivisionALinesMatchLeagueTable) {
  const FieldModel f = FieldModel::divisionA();
  ASSERT_EQ(f.lines.size(), 12u);
  expectLine(f, 0, "TopTouchLine", {-6000, 4500}, {6000, 4500});
  expectLine(f, 2, "LeftGoalLine", {-6000, -4500}, {-6000, 4500});
  expectLine(f, 5, "LeftPenaltyStretch", {-4200, -1800}, {-4200, 1800});
  expectLine(f, 9, "RightFieldRightPenaltyStretch", {6000, -1800}, {4200, -1800});
  expectLine(f, 10, "RightFieldLeftPenaltyStretch", {6000, 1800}, {4200, 1800});
  expectLine(f, 11, "CenterLine", {-6000, 0}, {6000, 0});
  EXPECT_EQ(f.lines[9].type, FieldShape::RightFieldRightPenaltyStretch);
  ASSERT_EQ(f.arcs.size(), 1u);
  EXPECT_EQ(f.arcs[0].name, "CenterCircle");
  EXPECT_EQ(f.arcs[0].radius, 500);
  EXPECT_EQ(f.arcs[0].a1, 0);
  EXPECT_DOUBLE_EQ(f.arcs[0].a2, 2 * kPi);
  EXPECT_EQ(f.arcs[0].thickness, 10);
}

TEST(GeometryIo, DivisionBLinesMatchLeagueTable) {
  const FieldModel f = FieldModel::divisionB();
  ASSERT_EQ(f.lines.size(), 12u);
  expectLine(f, 1, "BottomTouchLine", {-4500, -3000}, {4500, -3000});
  expectLine(f, 3, "RightGoalLine", {4500, -3000}, {4500, 3000});
  expectLine(f, 4, "HalfwayLine", {0, -3000}, {0, 3000});
  expectLine(f, 6, "RightPenaltyStretch", {3500, -1000}, {3500, 1000});
  expectLine(f, 7, "LeftFieldLeftPenaltyStretch", {-4500, -1000}, {-3500, -1000});
  expectLine(f, 8, "LeftFieldRightPenaltyStretch", {-4500, 1000}, {-3500, 1000});
  ASSERT_EQ(f.arcs.size(), 1u);
  EXPECT_EQ(f.arcs[0].center.x, 0);
  EXPECT_EQ(f.arcs[0].radius, 500);
  EXPECT_EQ(f.arcs[0].type, FieldShape::CenterCircle);
}

// ---- round trips ----

class GeometryRoundTrip : public testing::TestWithParam<char> {
 protected:
  FieldModel field() const { return GetParam() == 'A' ? FieldModel::divisionA() : FieldModel::divisionB(); }
};

TEST_P(GeometryRoundTrip, JsonKeepsEveryField) {
  const Geometry g = twoCameraGeometry(field());
  const std::string path = tempPath(std::string("roundtrip_") + GetParam() + ".json");
  saveGeometry(g, path);
  const Geometry back = loadGeometry(path);
  expectSameGeometry(g, back);
  ASSERT_NE(back.camera(1), nullptr);
  EXPECT_EQ(back.camera(1)->camera_id, 1u);
  EXPECT_EQ(back.camera(7), nullptr);
}

TEST_P(GeometryRoundTrip, YamlKeepsEveryField) {
  const Geometry g = twoCameraGeometry(field());
  const std::string path = tempPath(std::string("roundtrip_") + GetParam() + ".yaml");
  saveGeometry(g, path);
  expectSameGeometry(g, loadGeometry(path));
}

INSTANTIATE_TEST_SUITE_P(Divisions, GeometryRoundTrip, testing::Values('A', 'B'));

TEST(GeometryIo, CalibrationProtoCarriesDerivedPositionAndImageSize) {
  const CameraCalibration c = overheadCamera(3, 1500, -750);
  const auto m = toProto(c);
  EXPECT_NEAR(m.derived_camera_world_tx(), 1500, 0.01);
  EXPECT_NEAR(m.derived_camera_world_ty(), -750, 0.01);
  EXPECT_NEAR(m.derived_camera_world_tz(), 4123.4, 0.01);
  EXPECT_EQ(m.pixel_image_width(), 2448u);
  EXPECT_EQ(m.pixel_image_height(), 2048u);
  const auto unknown_size = toProto(tiltedCamera(1));
  EXPECT_FALSE(unknown_size.has_pixel_image_width());
  EXPECT_FALSE(unknown_size.has_pixel_image_height());
}

TEST(GeometryIo, JsonWithoutLinesGetsGeneratedMarkings) {
  // What SSL-Vision publishes after choosing a preset without "Update".
  auto m = toProto(Geometry{FieldModel::divisionA(), {}});
  m.mutable_field()->clear_field_lines();
  m.mutable_field()->clear_field_arcs();
  const Geometry g = loadGeometry(writeTemp("nolines.json", toCanonicalJson(m)));
  expectSameField(g.field, FieldModel::divisionA());
}

TEST(GeometryIo, JsonExplicitLinesAreKept) {
  FieldModel f = FieldModel::divisionB();
  f.lines.resize(2);
  f.lines[1].p2.x = 1234;
  f.arcs.clear();
  const Geometry g = loadGeometry(writeTemp("fewlines.json", toCanonicalJson(toProto(Geometry{f, {}}))));
  ASSERT_EQ(g.field.lines.size(), 2u);
  EXPECT_EQ(g.field.lines[1].p2.x, 1234);
  EXPECT_TRUE(g.field.arcs.empty());
}

TEST(GeometryIo, ShippedFieldFilesAreTheCodesPresets) {
  for (auto [name, preset] : {std::pair{"division_a.json", FieldModel::divisionA()},
                              std::pair{"division_b.json", FieldModel::divisionB()}}) {
    SCOPED_TRACE(name);
    const std::string path = std::string(DV_SOURCE_DIR) + "/config/fields/" + name;
    const Geometry g = loadGeometry(path);
    expectSameField(g.field, preset);
    EXPECT_TRUE(g.cameras.empty());
    // Byte for byte what saveGeometry writes, so they can be regenerated.
    EXPECT_EQ(readText(path), toCanonicalJson(toProto(Geometry{preset, {}})) + "\n");
  }
}

TEST(GeometryIo, YamlExampleLoads) {
  const Geometry g = loadGeometry(std::string(DV_SOURCE_DIR) + "/config/fields/example.yaml");
  EXPECT_EQ(g.field.field_length, 11000);  // override of the Division A preset
  EXPECT_EQ(g.field.field_width, 9000);    // from the preset
  expectLine(g.field, 0, "TopTouchLine", {-5500, 4500}, {5500, 4500});  // regenerated
  ASSERT_EQ(g.cameras.size(), 2u);
  ASSERT_NE(g.camera(1), nullptr);
  EXPECT_EQ(g.camera(1)->image_width, 2448u);
  EXPECT_NEAR(CameraModel(*g.camera(0)).position().z(), 4000, 1);
}

TEST(GeometryIo, YamlPresetWithOverridesRegeneratesLines) {
  const Geometry g = geometryFromYaml("field:\n  division: B\n  penalty_area_depth: 1200\n", "mem.yaml");
  EXPECT_EQ(g.field.field_length, 9000);
  EXPECT_EQ(g.field.penalty_area_depth, 1200);
  expectLine(g.field, 5, "LeftPenaltyStretch", {-3300, -1000}, {-3300, 1000});
  EXPECT_TRUE(g.cameras.empty());
}

TEST(GeometryIo, YamlExplicitLinesReplaceGeneratedOnes) {
  const Geometry g = geometryFromYaml(
      "field:\n  division: A\n  field_lines:\n"
      "    - {name: Middle, p1: [0, -100], p2: {x: 0, y: 100}, type: HalfwayLine}\n",
      "mem.yaml");
  ASSERT_EQ(g.field.lines.size(), 1u);
  EXPECT_EQ(g.field.lines[0].type, FieldShape::HalfwayLine);
  EXPECT_EQ(g.field.lines[0].p2.y, 100);
  EXPECT_EQ(g.field.lines[0].thickness, 10);
  EXPECT_TRUE(g.field.arcs.empty());
}

// ---- bad input: one clear message each ----

TEST(GeometryIoBadInput, MissingFile) {
  const std::string path = tempPath("does_not_exist.json");
  const std::string e = inputErrorOf([&] { loadGeometry(path); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("cannot open"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, UnknownExtension) {
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("field.txt", "{}")); });
  EXPECT_NE(e.find("field.txt"), std::string::npos) << e;
  EXPECT_NE(e.find(".json"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, MalformedJsonNamesFileAndPosition) {
  const std::string path = writeTemp("malformed.json", "{\"field\": {\n  \"fieldLength\": 9000,\n  oops\n}}");
  const std::string e = inputErrorOf([&] { loadGeometry(path); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("line 3, column 3"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, JsonNumberOverflowNamesFileAndPosition) {
  const std::string path = writeTemp("overflow.json", "{\"field\": {\n  \"fieldLength\": 1e400\n}}");
  const std::string e = inputErrorOf([&] { loadGeometry(path); });
  EXPECT_EQ(e.rfind(path + ": ", 0), 0u) << e;
  EXPECT_NE(e.find("line 2, column 18"), std::string::npos) << e;
  EXPECT_NE(e.find("number overflow"), std::string::npos) << e;
  EXPECT_EQ(e.find("json.exception"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, JsonUnknownField) {
  auto json = toCanonicalJson(toProto(Geometry{FieldModel::divisionB(), {}}));
  json.insert(1, "\"fieldSizes\": 3,");
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("unknown.json", json)); });
  EXPECT_NE(e.find("unknown.json"), std::string::npos) << e;
  EXPECT_NE(e.find("fieldSizes"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, JsonWrongShape) {
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("shape.json", "{\"field\": [1, 2]}")); });
  EXPECT_NE(e.find("shape.json: \"field\" must be an object"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, JsonWrongValueType) {
  auto json = toCanonicalJson(toProto(Geometry{FieldModel::divisionB(), {}}));
  json.replace(json.find("9000"), 4, "\"long\"");
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("valuetype.json", json)); });
  EXPECT_NE(e.find("valuetype.json"), std::string::npos) << e;
  EXPECT_NE(e.find("field.field_length"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, JsonUnknownNestedField) {
  auto json = toCanonicalJson(toProto(Geometry{FieldModel::divisionB(), {}}));
  json.insert(json.find("\"fieldLength\""), "\"fieldLenght\": 9000,");
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("nested.json", json)); });
  EXPECT_NE(e.find("nested.json"), std::string::npos) << e;
  EXPECT_NE(e.find("fieldLenght"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, JsonMissingRequiredField) {
  std::string json = toCanonicalJson(toProto(Geometry{FieldModel::divisionB(), {}}));
  const std::string key = "\"goalWidth\":1000,";
  ASSERT_NE(json.find(key), std::string::npos);
  json.erase(json.find(key), key.size());
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("required.json", json)); });
  EXPECT_NE(e.find("required.json"), std::string::npos) << e;
  EXPECT_NE(e.find("goal_width"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, JsonNonsenseDimension) {
  auto m = toProto(Geometry{FieldModel::divisionB(), {}});
  m.mutable_field()->set_goal_depth(0);
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("zero.json", toCanonicalJson(m))); });
  EXPECT_NE(e.find("zero.json"), std::string::npos) << e;
  EXPECT_NE(e.find("goal_depth"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, JsonDuplicateCamera) {
  Geometry g = twoCameraGeometry(FieldModel::divisionB());
  g.cameras[1] = overheadCamera(0, 2250, 0);
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("dup.json", toCanonicalJson(toProto(g)))); });
  EXPECT_NE(e.find("camera 0 is given twice"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, MalformedYamlNamesLineAndColumn) {
  const std::string path = writeTemp("malformed.yaml", "field:\n  division: A\n  field_length: [12000\n");
  const std::string e = inputErrorOf([&] { loadGeometry(path); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("malformed YAML at line"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, YamlWrongType) {
  const std::string path = writeTemp("type.yaml", "field:\n  division: A\n  field_width: wide\n");
  const std::string e = inputErrorOf([&] { loadGeometry(path); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("line 3, column 16"), std::string::npos) << e;
  EXPECT_NE(e.find("'field_width' must be an integer"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, YamlUnknownKey) {
  const std::string e = inputErrorOf([] { geometryFromYaml("field:\n  division: B\n  feild_length: 9000\n", "k.yaml"); });
  EXPECT_NE(e.find("k.yaml: line 3, column 3: unknown key 'feild_length'"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, YamlCameraMissingKey) {
  const std::string e = inputErrorOf([] {
    geometryFromYaml("field: {division: B}\ncameras:\n  - {camera_id: 0, focal_length: 900}\n", "c.yaml");
  });
  EXPECT_NE(e.find("c.yaml: line 3"), std::string::npos) << e;
  EXPECT_NE(e.find("missing required key 'principal_point_x'"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, YamlBadDivision) {
  const std::string e = inputErrorOf([] { geometryFromYaml("field:\n  division: C\n", "d.yaml"); });
  EXPECT_NE(e.find("'division' must be A or B"), std::string::npos) << e;
}

TEST(GeometryIoBadInput, ImplausibleCalibrations) {
  struct Case {
    const char* what;
    std::function<void(CameraCalibration&)> spoil;
    const char* expected;
  };
  const Case cases[] = {
      {"zero focal", [](CameraCalibration& c) { c.focal_length = 0; }, "focal_length"},
      {"negative focal", [](CameraCalibration& c) { c.focal_length = -900; }, "focal_length"},
      {"NaN", [](CameraCalibration& c) { c.ty = std::nan(""); }, "NaN"},
      {"infinite", [](CameraCalibration& c) { c.distortion = INFINITY; }, "infinite"},
      {"zero quaternion", [](CameraCalibration& c) { c.q0 = c.q1 = c.q2 = c.q3 = 0; }, "quaternion"},
      {"below field", [](CameraCalibration& c) { c.tz = -c.tz; }, "below the field"},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.what);
    CameraCalibration c = overheadCamera(2, 0, 0);
    ASSERT_FALSE(calibrationProblem(c).has_value());
    k.spoil(c);
    const std::string e = inputErrorOf([&] { validateCalibration(c, "udp 127.0.0.1"); });
    EXPECT_NE(e.find("udp 127.0.0.1: camera 2"), std::string::npos) << e;
    EXPECT_NE(e.find(k.expected), std::string::npos) << e;
  }
}

TEST(GeometryIoBadInput, NonUnitQuaternionIsImplausible) {
  CameraCalibration c = overheadCamera(2, 0, 0);
  c.q0 *= 1.0 + 2 * kQuaternionLengthTolerance;
  const std::string e = inputErrorOf([&] { validateCalibration(c, "cam.json"); });
  EXPECT_NE(e.find("cam.json: camera 2"), std::string::npos) << e;
  EXPECT_NE(e.find("not 1"), std::string::npos) << e;
  // Float rounding of a normalised quaternion passes.
  CameraCalibration rounded = overheadCamera(2, 0, 0);
  rounded.q0 = float(rounded.q0), rounded.q1 = float(rounded.q1);
  rounded.q2 = float(rounded.q2), rounded.q3 = float(rounded.q3);
  EXPECT_FALSE(calibrationProblem(rounded).has_value());
}

TEST(GeometryIoBadInput, ZeroImageWidthWhereGivenIsRefused) {
  Geometry g = twoCameraGeometry(FieldModel::divisionB());
  auto m = toProto(g);
  m.mutable_calib(0)->set_pixel_image_width(0);
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("zerowidth.json", toCanonicalJson(m))); });
  EXPECT_NE(e.find("zerowidth.json: camera 0"), std::string::npos) << e;
  EXPECT_NE(e.find("pixel_image_width is 0"), std::string::npos) << e;
  std::string yaml = toYaml(g);
  yaml.replace(yaml.find("pixel_image_width: 2448"), 23, "pixel_image_width: 0");
  const std::string y = inputErrorOf([&] { geometryFromYaml(yaml, "zerowidth.yaml"); });
  EXPECT_NE(y.find("zerowidth.yaml: line"), std::string::npos) << y;
  EXPECT_NE(y.find("'pixel_image_width' is 0"), std::string::npos) << y;
}

TEST(GeometryIoBadInput, FieldLineFarBeyondTheFieldIsRefused) {
  Geometry g{FieldModel::divisionB(), {}};
  g.field.lines[0].p1.x = -1e20;
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("farline.json", toCanonicalJson(toProto(g)))); });
  EXPECT_NE(e.find("farline.json: field: field line '" + g.field.lines[0].name + "' lies beyond the field"),
            std::string::npos) << e;
  const std::string y = inputErrorOf([&] { geometryFromYaml(toYaml(g), "farline.yaml"); });
  EXPECT_NE(y.find("farline.yaml: line"), std::string::npos) << y;
  EXPECT_NE(y.find("lies beyond the field"), std::string::npos) << y;
}

TEST(GeometryIoBadInput, ImplausibleCalibrationInFile) {
  Geometry g = twoCameraGeometry(FieldModel::divisionA());
  g.cameras[0].focal_length = -1;
  const std::string e = inputErrorOf([&] { loadGeometry(writeTemp("badcam.json", toCanonicalJson(toProto(g)))); });
  EXPECT_NE(e.find("badcam.json: camera 0"), std::string::npos) << e;
  const std::string y = inputErrorOf([&] { geometryFromYaml(toYaml(g), "badcam.yaml"); });
  EXPECT_NE(y.find("badcam.yaml: line"), std::string::npos) << y;
  EXPECT_NE(y.find("focal_length"), std::string::npos) << y;
}

}  // namespace
}  // namespace dv

// Lens terms in geometry files and packets: the YAML and JSON forms keep
// them in dotvision's own keys, bad keys get one clear message, and the SSL
// message carries the league model's best fit, which stands in for the lens
// to a few millimetres where dropping the terms would not.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "geometry/calibration/league_fit.h"
#include "geometry/geometry_io.h"
#include "geometry/proto_json.h"
#include "synth/scene.h"
#include "temp_dir.h"

namespace dv {
namespace {

// The issue's lens (k1 0.026, k2 -0.004, small tangential terms) on a
// 2448 x 2048 camera 4.5 m over a Division B half, looking straight down.
CameraCalibration issueLens() {
  CameraCalibration c = makeCamera(0, {-2250, 0, 4500}, {-2250, 0, 0}, 1300, 0.026, {6.5, -4}, 2448, 2048).calib;
  c.lens = {-0.004, 0, 0.0006, -0.0004};
  return c;
}

Geometry geometryWith(const CameraCalibration& c) {
  Geometry g;
  g.field = FieldModel::divisionB();
  g.cameras.push_back(c);
  CameraCalibration plain = c;
  plain.camera_id = 1, plain.lens = {};
  g.cameras.push_back(plain);
  return g;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected InputError";
  return "";
}

TEST(GeometryLens, LeagueFitStandsInForTheLens) {
  const CameraCalibration lens = issueLens();
  CameraCalibration dropped = lens;
  dropped.lens = {};
  const ModelDifference drop = modelDifference(lens, dropped);
  const LeagueFit fit = leagueFit(lens);
  EXPECT_FALSE(fit.calibration.lens.any());
  std::printf("[ league model for the issue's lens ] terms dropped: %.2f mm mean, %.2f mm max; best fit: %.2f mm mean, "
              "%.2f mm max (k %.4f, f %.1f)\n",
              drop.mean_mm, drop.max_mm, fit.residual.mean_mm, fit.residual.max_mm, fit.calibration.distortion,
              fit.calibration.focal_length);
  EXPECT_LT(fit.residual.mean_mm, 0.5 * drop.mean_mm);
  EXPECT_GT(fit.residual.mean_mm, 0.3);  // the league's model cannot follow this lens
  // Without terms the fit is the calibration itself.
  EXPECT_EQ(leagueFit(dropped).calibration, dropped);
  EXPECT_EQ(leagueFit(dropped).residual.mean_mm, 0);
}

TEST(GeometryLens, PacketsCarryTheLeagueFit) {
  const CameraCalibration lens = issueLens();
  const auto m = toProto(lens);
  const CameraCalibration fit = leagueFit(lens).calibration;
  EXPECT_FLOAT_EQ(m.distortion(), float(fit.distortion));
  EXPECT_FLOAT_EQ(m.focal_length(), float(fit.focal_length));
  EXPECT_FLOAT_EQ(m.principal_point_x(), float(fit.principal_point_x));
  EXPECT_FLOAT_EQ(m.tz(), float(fit.tz));
  EXPECT_NE(m.distortion(), float(lens.distortion));
}

TEST(GeometryLens, ProcessorsKeepTheLensAtWirePrecision) {
  const Geometry g = geometryWith(issueLens());
  const Geometry used = withWirePrecision(g, "g");
  ASSERT_EQ(used.cameras.size(), 2u);
  EXPECT_EQ(used.cameras[0].lens.k2, double(float(-0.004)));
  EXPECT_EQ(used.cameras[0].focal_length, double(float(g.cameras[0].focal_length)));
  EXPECT_EQ(used.cameras[0].tz, double(float(g.cameras[0].tz)));
  // A camera without terms is exactly what the wire carries.
  EXPECT_EQ(used.cameras[1], geometryFromProto(toProto(g), "g").cameras[1]);
}

TEST(GeometryLens, YamlKeepsTheTerms) {
  const Geometry g = geometryWith(issueLens());
  const std::string text = toYaml(g);
  EXPECT_NE(text.find("lens:"), std::string::npos);
  const Geometry back = geometryFromYaml(text, "t.yaml");
  ASSERT_EQ(back.cameras.size(), 2u);
  EXPECT_EQ(back.cameras[0].lens, g.cameras[0].lens);
  EXPECT_EQ(back.cameras[0].distortion, g.cameras[0].distortion);
  EXPECT_FALSE(back.cameras[1].lens.any());
  // A camera without terms is written as before: no lens key.
  Geometry plain = g;
  plain.cameras.erase(plain.cameras.begin());
  EXPECT_EQ(toYaml(plain).find("lens"), std::string::npos);
}

TEST(GeometryLens, YamlBadTermsAreNamed) {
  const std::string text = toYaml(geometryWith(issueLens()));
  // Each edit swaps one token of the written text.
  const auto swapped = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.substr(0, at) + to + text.substr(at + from.size());
  };
  std::string bad = swapped("k3", "k4");
  EXPECT_NE(errorOf([&] { geometryFromYaml(bad, "g.yaml"); }).find("unknown key 'k4' in 'lens'"), std::string::npos);
  bad = swapped("k2: -", "k2: x");
  EXPECT_NE(errorOf([&] { geometryFromYaml(bad, "g.yaml"); }).find("'lens.k2' must be a number"), std::string::npos);
}

TEST(GeometryLens, JsonHoldsTheLeagueFitAndTheFullLens) {
  const Geometry g = geometryWith(issueLens());
  const std::string text = toJson(g);
  const nlohmann::json j = nlohmann::json::parse(text);
  ASSERT_TRUE(j.contains("dotvisionLenses"));
  ASSERT_EQ(j["dotvisionLenses"].size(), 1u);  // only the camera with terms
  // "calib" is what a league reader sees: the fit, as packets carry it.
  EXPECT_FLOAT_EQ(j["calib"][0]["distortion"].get<float>(), toProto(g.cameras[0]).distortion());
  const Geometry back = geometryFromJson(text, "g.json");
  ASSERT_EQ(back.cameras.size(), 2u);
  EXPECT_EQ(back.cameras[0].lens, g.cameras[0].lens);
  EXPECT_EQ(back.cameras[0].focal_length, g.cameras[0].focal_length);
  EXPECT_EQ(back.cameras[0].tz, g.cameras[0].tz);
  EXPECT_EQ(back.cameras[0].image_width, 2448u);
  // Without terms the file is the canonical SSL_GeometryData, as before.
  Geometry plain = g;
  plain.cameras.erase(plain.cameras.begin());
  EXPECT_EQ(toJson(plain), toCanonicalJson(toProto(plain)));
  // And through a file.
  const TempDir dir("dv_geometry_lens_test");
  saveGeometry(g, dir.file("g.json"));
  EXPECT_EQ(loadGeometry(dir.file("g.json")).cameras[0], back.cameras[0]);
}

// The fuzz targets' seeds with lens terms are valid files, in both forms.
TEST(GeometryLens, FuzzSeedsWithLensesLoad) {
  for (const char* f : {"/fuzz/corpus/geometry_json/lens.json", "/fuzz/corpus/geometry_yaml/lens.yaml"}) {
    const Geometry g = loadGeometry(std::string(DV_SOURCE_DIR) + f);
    ASSERT_EQ(g.cameras.size(), 1u) << f;
    EXPECT_EQ(g.cameras[0].lens.k2, -0.004) << f;
    EXPECT_EQ(g.cameras[0].distortion, 0.026) << f;
  }
}

TEST(GeometryLens, JsonBadLensEntriesAreNamed) {
  const std::string text = toJson(geometryWith(issueLens()));
  auto with = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = nlohmann::json::parse(text);
    edit(j);
    return errorOf([&] { geometryFromJson(j.dump(), "g.json"); });
  };
  EXPECT_NE(with([](auto& j) { j["dotvisionLenses"][0]["k9"] = 1; }).find("dotvisionLenses[0]: unknown key \"k9\""),
            std::string::npos);
  EXPECT_NE(with([](auto& j) { j["dotvisionLenses"][0].erase("p2"); }).find("dotvisionLenses[0] lacks \"p2\""),
            std::string::npos);
  EXPECT_NE(with([](auto& j) { j["dotvisionLenses"][0]["cameraId"] = 7; }).find("camera 7 is not in \"calib\""),
            std::string::npos);
  EXPECT_NE(with([](auto& j) { j["dotvisionLenses"][0]["k2"] = "a"; }).find("\"k2\" must be a number"),
            std::string::npos);
  EXPECT_NE(with([](auto& j) { j["dotvisionLenses"] = 3; }).find("\"dotvisionLenses\" must be a list"),
            std::string::npos);
  EXPECT_NE(with([](auto& j) { j["dotvisionLenses"][0]["focalLength"] = -5; }).find("implausible calibration"),
            std::string::npos);
}

}  // namespace
}  // namespace dv

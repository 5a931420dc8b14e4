// The console in a real browser (Debian's chromium, headless, driven by
// chromedriver) against a live `dotvision serve`: the field page draws the
// robots the cameras report, the camera page loads frames of the size it
// asked for and switches to a grid layer whose hover shows a robot's field
// point, and a robot height changed on the settings page is refused
// with a wrong token and, with the printed one, reaches the processors and
// the config file; the calibration page runs a calibration and shows its
// verdict, figures and overlay, and accepting it changes the geometry, and
// known field points picked on its image calibrate in the points mode; the
// colors page draws the learned classes and recent blobs; the status page
// shows serve's log, never the token. Screenshots go to
// <build>/test_artifacts/console/.
// Skipped, saying why, where chromium or chromedriver is not installed.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include <nlohmann/json.hpp>

#include "console_serve.h"
#include "geometry/camera_model.h"
#include "geometry/geometry_io.h"
#include "webdriver.h"

namespace dv {
namespace {

using nlohmann::json;
const std::string kArtifacts = std::string(DV_BINARY_DIR) + "/test_artifacts/console/";

class ConsoleBrowser : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!WebDriver::skipReason().empty()) return;
    serve_ = new ConsoleServe("dv_console_browser");
    started_ = serve_->start();
    profile_ = new TempDir("dv_console_chromium");
    if (started_) driver_ = new WebDriver(profile_->path().string());
  }
  static void TearDownTestSuite() {
    delete driver_;
    delete serve_;
    delete profile_;
    driver_ = nullptr;
    serve_ = nullptr;
    profile_ = nullptr;
  }
  void SetUp() override {
    if (const std::string why = WebDriver::skipReason(); !why.empty()) GTEST_SKIP() << why;
    ASSERT_TRUE(started_) << serve_->log();
    ASSERT_TRUE(driver_ && driver_->ok()) << (driver_ ? driver_->why() : "");
  }
  static json apiJson(const std::string& path) {
    httplib::Client c("127.0.0.1", serve_->port());
    c.set_read_timeout(30, 0);
    auto r = c.Get(path.c_str());
    return r && r->status == 200 ? json::parse(r->body) : json();
  }
  static double heightInUse() {
    const json s = apiJson("/api/status");
    return s.is_object() && !s["cameras"].empty() ? s["cameras"][0]["robot_height_mm"]["yellow"].get<double>() : -1;
  }

  // Clicks Run on the Calibration page and waits for the run to end: its
  // figures' text ("" when it did not end).
  static std::string runOnCalibrationPage(WebDriver& d) {
    d.click(d.find("#run"));
    if (!d.waitUntil("return document.getElementById('state').dataset.state == 'done'", 300)) return "";
    return d.execute("return document.getElementById('figures').innerText");
  }

  static ConsoleServe* serve_;
  static bool started_;
  static TempDir* profile_;
  static WebDriver* driver_;
};
ConsoleServe* ConsoleBrowser::serve_ = nullptr;
bool ConsoleBrowser::started_ = false;
TempDir* ConsoleBrowser::profile_ = nullptr;
WebDriver* ConsoleBrowser::driver_ = nullptr;

TEST_F(ConsoleBrowser, FieldPageDrawsTheRobotsEveryCameraReports) {
  WebDriver& d = *driver_;
  d.navigate(serve_->url("/"));
  const std::string cam0 = "document.querySelectorAll('#detections [data-camera=\"0\"] circle.robot').length";
  EXPECT_TRUE(d.waitUntil("return " + cam0 + " >= " + std::to_string(ConsoleServe::kCamera0Robots - 1) +
                          " && document.querySelectorAll('#detections [data-camera=\"1\"] circle.robot').length > 0"))
      << d.execute("return document.getElementById('detections').innerHTML");
  // What is drawn is what the page received: one circle per robot reported.
  const json drawn = d.execute(
      "return [document.querySelectorAll('#detections circle.robot').length, "
      "Number(document.getElementById('field').dataset.robots)]");
  EXPECT_EQ(drawn[0], drawn[1]) << drawn.dump();
  // The field's lines, both footprints, a badge per camera with its health.
  EXPECT_GE(d.execute("return document.querySelectorAll('#lines .line').length"), 10);
  EXPECT_EQ(d.execute("return document.querySelectorAll('#footprints polygon').length"), 2);
  // Both cameras deliver frames: each badge says ok, or degraded where a
  // loaded machine (CI runs two tests at once) slows them below their rate.
  EXPECT_TRUE(d.waitUntil("const b = [...document.querySelectorAll('#badges .badge')]; return b.length == 2 && "
                          "b.every(x => x.classList.contains('ok') || x.classList.contains('degraded')) && "
                          "b[0].textContent.startsWith('cam 0') && b[1].textContent.startsWith('cam 1')"))
      << d.execute("return document.getElementById('badges').innerHTML");
  EXPECT_TRUE(d.screenshot(kArtifacts + "field.png"));
}

TEST_F(ConsoleBrowser, CameraPageLoadsFramesOfTheSizeItAsked) {
  WebDriver& d = *driver_;
  d.navigate(serve_->url("/camera.html?camera=1"));
  // The page keeps replacing the image: note one as it loads.
  d.execute(
      "const i = document.getElementById('snapshot'); i.addEventListener('load', () => { "
      "if (i.naturalWidth > 0) window.loadedImage = [i.naturalWidth, i.naturalHeight, "
      "new URL(i.src).searchParams.get('width'), i.src]; }); return true");
  ASSERT_TRUE(d.waitUntil("const i = document.getElementById('snapshot'); "
                          "return Number(i.dataset.loaded) >= 3 && Array.isArray(window.loadedImage)"))
      << d.execute("return document.getElementById('snapshot').src");
  const json img = d.execute("return window.loadedImage");
  ASSERT_TRUE(img.is_array()) << img.dump();
  const int asked = std::stoi(img[2].get<std::string>());
  EXPECT_GT(asked, 500) << img.dump();  // a 1280 px window asks for its width, at most 960
  EXPECT_LE(asked, 960) << img.dump();
  EXPECT_EQ(img[0], asked) << img.dump();
  EXPECT_EQ(img[1], static_cast<int>(std::lround(double(ConsoleServe::kHeight) * asked / ConsoleServe::kWidth)))
      << img.dump();
  EXPECT_NE(img[3].get<std::string>().find("/api/cameras/1/snapshot.jpg"), std::string::npos) << img.dump();
  EXPECT_TRUE(d.waitUntil("return document.getElementById('badge').textContent.startsWith('cam 1')"));
  EXPECT_TRUE(d.screenshot(kArtifacts + "camera.png"));
  d.navigate(serve_->url("/status.html"));
  EXPECT_TRUE(d.waitUntil("return document.querySelectorAll('#status tbody tr').length == 2"));
  EXPECT_TRUE(d.screenshot(kArtifacts + "status.png"));
}

// The camera page switches to a picture of the pixel stage (the blob score
// with the blobs): it has the rectified grid's aspect, and hovering over a
// robot there shows the field point the camera reports for it.
TEST_F(ConsoleBrowser, CameraPageSwitchesToAGridLayerAndHoversOnTheField) {
  WebDriver& d = *driver_;
  const json grid = apiJson("/api/cameras/0/grid");
  ASSERT_TRUE(grid.is_object()) << serve_->log();
  const int gw = grid["width"], gh = grid["height"];
  d.navigate(serve_->url("/camera.html?camera=0"));
  ASSERT_TRUE(d.waitUntil("return Number(document.getElementById('snapshot').dataset.loaded) >= 1"));
  // The page keeps replacing the image, at once when a picture took longer
  // than its interval (a loaded machine): note, as it loads, the first one
  // with these layers.
  d.execute(
      "const i = document.getElementById('snapshot'); i.addEventListener('load', () => { "
      "const q = new URL(i.src).searchParams; "
      "if (!window.seen && i.naturalWidth > 0 && q.get('layer') == 'score,blobs,lines,detections') "
      "window.seen = [i.naturalWidth, i.naturalHeight, Number(q.get('width'))]; }); return true");
  d.click(d.find("input[name=base][value=score]"));
  d.click(d.find("#layer-blobs"));
  ASSERT_TRUE(d.waitUntil("return Array.isArray(window.seen)"))
      << d.execute("return document.getElementById('snapshot').src");
  const json seen = d.execute("return window.seen");
  const int width = std::min(gw, seen[2].get<int>());
  EXPECT_EQ(seen[0], width) << seen.dump() << grid.dump();
  EXPECT_NEAR(seen[1].get<double>(), double(gh) * width / gw, 1) << seen.dump() << grid.dump();
  EXPECT_TRUE(d.screenshot(kArtifacts + "camera_score_blobs.png"));

  // Hover over a robot camera 0 reports: the page shows its field point.
  json robot;
  ASSERT_TRUE(ConsoleServe::waitFor([&] {
    const json det = apiJson("/api/detections");
    if (det.is_object() && det["cameras"][0]["detection"].is_object())
      robot = det["cameras"][0]["detection"].value("robotsYellow", json::array())[0];
    return robot.is_object();
  }));
  const double gx = (robot["x"].get<double>() - grid["x0_mm"].get<double>()) / grid["mm_per_cell"].get<double>();
  const double gy = (grid["y0_mm"].get<double>() - robot["y"].get<double>()) / grid["mm_per_cell"].get<double>();
  const json field = d.execute(
      "const i = document.getElementById('snapshot'), r = i.getBoundingClientRect(); "
      "i.dispatchEvent(new MouseEvent('mousemove', {bubbles: true, clientX: r.left + (arguments[0] + 0.5) / "
      "arguments[2] * r.width, clientY: r.top + (arguments[1] + 0.5) / arguments[3] * r.height})); "
      "return document.getElementById('hover').dataset.field",
      {gx, gy, gw, gh});
  ASSERT_TRUE(field.is_string()) << field.dump();
  const std::string xy = field.get<std::string>();
  const size_t comma = xy.find(',');
  ASSERT_NE(comma, std::string::npos) << xy;
  // A pixel of the page's picture is about 1.1 grid cells (6 mm) wide.
  EXPECT_NEAR(std::stod(xy.substr(0, comma)), robot["x"].get<double>(), 15) << xy << " " << robot.dump();
  EXPECT_NEAR(std::stod(xy.substr(comma + 1)), robot["y"].get<double>(), 15) << xy << " " << robot.dump();
  EXPECT_NE(d.execute("return document.getElementById('hover').textContent").get<std::string>().find("grid cell"),
            std::string::npos);
}

TEST_F(ConsoleBrowser, HeightSetOnTheSettingsPageReachesTheProcessorAndTheFile) {
  WebDriver& d = *driver_;
  ASSERT_TRUE(ConsoleServe::waitFor([] { return heightInUse() == 140; }));
  const std::string loaded = "return document.getElementById('robot_heights.default').value == '140'";
  auto setDefault = [&](const std::string& mm, const char* button) {
    const std::string input = d.find("[id='robot_heights.default']");
    ASSERT_FALSE(input.empty());
    d.clear(input);
    d.type(input, mm);
    d.click(d.find(button));
  };
  // A wrong token: refused, shown as such, nothing changes.
  d.navigate(serve_->url("/settings.html?try=1#token=0000"));
  ASSERT_TRUE(d.waitUntil(loaded));
  setDefault("133", "#apply-save");
  EXPECT_TRUE(d.waitUntil("return document.getElementById('result').dataset.status == '403'"))
      << d.execute("return document.getElementById('result').textContent");
  EXPECT_TRUE(d.screenshot(kArtifacts + "settings_refused.png"));
  EXPECT_EQ(heightInUse(), 140);
  EXPECT_NE(serve_->configText().find("default: 140"), std::string::npos);

  // The token serve printed: applied and saved.
  ASSERT_FALSE(serve_->printedToken().empty()) << serve_->log();
  d.navigate(serve_->url("/settings.html?try=2#token=" + serve_->printedToken()));
  ASSERT_TRUE(d.waitUntil(loaded));
  setDefault("133", "#apply-save");
  EXPECT_TRUE(d.waitUntil("return document.getElementById('result').dataset.status == '200'"))
      << d.execute("return document.getElementById('result').textContent");
  EXPECT_TRUE(ConsoleServe::waitFor([] { return heightInUse() == 133; }));
  EXPECT_NE(serve_->configText().find("default: 133   # the league's usual"), std::string::npos)
      << serve_->configText();
  // The page shows the new value, read back from the server.
  EXPECT_TRUE(d.waitUntil("return document.getElementById('robot_heights.default').value == '133'"));
  EXPECT_TRUE(d.screenshot(kArtifacts + "settings.png"));
}

TEST_F(ConsoleBrowser, CalibrationPageRunsAndShowsAResult) {
  WebDriver& d = *driver_;
  const json before = apiJson("/api/geometry");
  d.navigate(serve_->url("/calibration.html?camera=0#token=" + serve_->printedToken()));
  ASSERT_TRUE(d.waitUntil("return document.getElementById('state').dataset.state == 'none'"))
      << d.execute("return document.body.innerText");
  d.execute("document.getElementById('region').value = 'x<0'; document.getElementById('height').value = '5000'");
  const std::string figures = runOnCalibrationPage(d);
  ASSERT_FALSE(figures.empty()) << d.execute("return document.body.innerText");
  EXPECT_NE(figures.find("passed"), std::string::npos) << figures;
  EXPECT_NE(figures.find("overlap ratio"), std::string::npos) << figures;
  // The overlay of the frame calibrated, 960 px wide at most.
  ASSERT_TRUE(d.waitUntil("const i = document.getElementById('image'); "
                          "return i.complete && i.naturalWidth > 0 && i.src.includes('/calibration/overlay.jpg')"));
  EXPECT_EQ(d.execute("return document.getElementById('image').naturalWidth"), 960);
  EXPECT_EQ(d.execute("return document.getElementById('accept').disabled"), false);
  EXPECT_TRUE(d.screenshot(kArtifacts + "calibration.png"));
  d.click(d.find("#accept"));
  EXPECT_TRUE(d.waitUntil("return document.getElementById('state').dataset.state == 'accepted'"))
      << d.execute("return document.getElementById('notes').textContent");
  EXPECT_NE(apiJson("/api/geometry"), before);
  EXPECT_TRUE(d.screenshot(kArtifacts + "calibration_accepted.png"));
}

// The four-point fallback: known field points chosen from the list and
// clicked where camera 1's true calibration sees them; the run on them
// passes in the points mode.
TEST_F(ConsoleBrowser, CalibrationPagePicksKnownFieldPointsOnTheImage) {
  WebDriver& d = *driver_;
  httplib::Client c("127.0.0.1", serve_->port());
  c.set_read_timeout(30, 0);
  auto g = c.Get("/api/geometry");
  ASSERT_TRUE(g && g->status == 200);
  const Geometry geometry = geometryFromJson(g->body, "/api/geometry");
  ASSERT_NE(geometry.camera(1), nullptr);
  const CameraModel truth(*geometry.camera(1));
  d.navigate(serve_->url("/calibration.html?camera=1#token=" + serve_->printedToken()));
  ASSERT_TRUE(d.waitUntil("const i = document.getElementById('image'); "
                          "return document.getElementById('state').dataset.state == 'none' && "
                          "document.getElementById('known').options.length > 10 && i.complete && i.naturalWidth > 0"))
      << d.execute("return document.body.innerText");
  d.execute("document.getElementById('picker').open = true");
  const std::pair<int, int> points[] = {{0, 3000}, {0, -3000}, {4500, 3000}, {4500, -3000}, {3500, 1000}, {3500, -1000}};
  for (const auto& [x, y] : points) {
    const auto px = truth.fieldToImage({double(x), double(y), 0});
    ASSERT_TRUE(px.has_value()) << x << ", " << y;
    const json chosen = d.execute(
        "const s = document.getElementById('known'); "
        "const o = [...s.options].find((o) => o.text.endsWith(`(${arguments[0]}, ${arguments[1]})`)); "
        "if (!o) return false; s.value = o.value; "
        "const i = document.getElementById('image'), r = i.getBoundingClientRect(); "
        "i.dispatchEvent(new MouseEvent('click', {bubbles: true, clientX: r.left + (arguments[2] + 0.5) / "
        "arguments[4] * r.width, clientY: r.top + (arguments[3] + 0.5) / arguments[5] * r.height})); "
        "return true",
        {x, y, px->u, px->v, ConsoleServe::kWidth, ConsoleServe::kHeight});
    ASSERT_EQ(chosen, true) << "no known point (" << x << ", " << y << ") in the list";
  }
  EXPECT_EQ(d.execute("return document.getElementById('picked').dataset.count"), "6");
  EXPECT_EQ(d.execute("return document.querySelectorAll('#view .pick-mark').length"), 6);
  EXPECT_TRUE(d.screenshot(kArtifacts + "calibration_points_picked.png"));
  d.execute("document.getElementById('height').value = '5000'");
  const std::string figures = runOnCalibrationPage(d);
  ASSERT_FALSE(figures.empty()) << d.execute("return document.body.innerText");
  EXPECT_NE(figures.find("passed"), std::string::npos) << figures;
  EXPECT_NE(figures.find("points"), std::string::npos) << figures;
  EXPECT_TRUE(d.screenshot(kArtifacts + "calibration_points.png"));
}

TEST_F(ConsoleBrowser, ColorsPageDrawsTheClassesAndRecentBlobs) {
  WebDriver& d = *driver_;
  d.navigate(serve_->url("/colors.html"));
  EXPECT_TRUE(d.waitUntil("return document.querySelectorAll('#chroma .class-ring').length == 7 && "
                          "document.querySelectorAll('#chroma .blob-dot').length > 20"))
      << d.execute("return document.body.innerText");
  EXPECT_NE(d.execute("return document.getElementById('separations').textContent").get<std::string>().find("yellow–blue"),
            std::string::npos);
  EXPECT_TRUE(d.screenshot(kArtifacts + "colors.png"));
}

TEST_F(ConsoleBrowser, StatusPageShowsTheLogButNotTheToken) {
  WebDriver& d = *driver_;
  d.navigate(serve_->url("/status.html"));
  d.execute("document.getElementById('warnings-only').click()");  // every line, not only the warnings
  EXPECT_TRUE(d.waitUntil("return document.getElementById('log').innerText.includes('running 2 camera(s)')"))
      << d.execute("return document.getElementById('log').innerText");
  ASSERT_FALSE(serve_->printedToken().empty());
  EXPECT_EQ(d.execute("return document.body.innerText").get<std::string>().find(serve_->printedToken()),
            std::string::npos);
  EXPECT_EQ(apiJson("/api/log").dump().find(serve_->printedToken()), std::string::npos);
  EXPECT_TRUE(d.screenshot(kArtifacts + "status_log.png"));
}

}  // namespace
}  // namespace dv

// Synthetic renderer: objects appear where the camera model puts them,
// the Bayer mosaic has its colors at the right sites, truth lists exactly the
// visible objects, output is deterministic for a seed, and the written
// geometry.json loads back with the true calibration.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "dotvision/ssl_detection.pb.h"
#include "geometry/geometry_io.h"
#include "geometry/proto_json.h"
#include "synth/renderer.h"
#include "synth/scene.h"
#include "synth/sensor_model.h"
#include "temp_dir.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

// A small clean scene: one camera, no noise, no blur, flat light, and
// pattern colors that are pure channels so coverage can be read from them.
SceneSpec cleanScene(FieldPoint cam_pos, FieldPoint look_at, double focal, double k,
                     uint32_t w = 320, uint32_t h = 256) {
  SceneSpec s;
  s.name = "test";
  s.seed = 3;
  s.cameras.push_back(makeCamera(0, cam_pos, look_at, focal, k, {2.5, -1.5}, w, h));
  s.ball.present = false;
  s.noise_sigma = 0;
  s.shot_noise = 0;
  s.lens_blur_px = 0;
  s.lighting.object_shadow = 0;
  s.antialias = 2;
  s.bayer = false;
  SceneMaterials& m = s.materials;
  m.carpet = {0, 100, 0};
  m.carpet_texture = 0;
  m.robot_top = {0, 0, 0};
  m.robot_body = {0, 0, 0};
  m.blue = {0, 0, 250};
  m.yellow = {0, 0, 250};
  m.green = {0, 250, 0};
  m.pink = {250, 0, 0};
  m.line = {0, 100, 0};
  m.ball = {0, 0, 250};
  return s;
}

// Coverage-weighted centroid of the blue channel (B, G, R order) in a window.
ImagePx blueCentroid(const cv::Mat& bgr, ImagePx around, int radius, double* mass = nullptr) {
  double sw = 0, su = 0, sv = 0;
  for (int v = int(around.v) - radius; v <= int(around.v) + radius; ++v)
    for (int u = int(around.u) - radius; u <= int(around.u) + radius; ++u) {
      if (u < 0 || v < 0 || u >= bgr.cols || v >= bgr.rows) continue;
      const double w = bgr.type() == CV_32FC3 ? bgr.at<cv::Vec3f>(v, u)[0]
                                              : double(bgr.at<cv::Vec3b>(v, u)[0]);
      sw += w, su += w * u, sv += w * v;
    }
  if (mass) *mass = sw;
  return {su / sw, sv / sw};
}

TEST(SynthRender, RobotCenterBlobWhereTheCameraModelSaysTopDown) {
  SceneSpec s = cleanScene({0, 0, 3000}, {0, 0, 0}, 600, 0.0);
  s.robots.push_back({Team::Blue, 5, {137, -83}, 0.7, 140, {}, 0});
  const Renderer r(s);
  const RenderedFrame f = r.render(0, 0);
  ASSERT_EQ(f.truth.robots_blue_size(), 1);
  const auto& t = f.truth.robots_blue(0);
  const auto want = CameraModel(s.cameras[0].calib).fieldToImage({137, -83, 140});
  ASSERT_TRUE(want);
  EXPECT_NEAR(t.pixel_x(), want->u, 1e-3);
  EXPECT_NEAR(t.pixel_y(), want->v, 1e-3);
  const ImagePx c = blueCentroid(f.image, *want, 9);
  EXPECT_NEAR(c.u, want->u, 0.3);
  EXPECT_NEAR(c.v, want->v, 0.3);
}

TEST(SynthRender, RobotCenterBlobWhereTheCameraModelSaysTiltedAndDistorted) {
  // An oblique camera with strong distortion; robots spread over the image,
  // one near a corner where distortion matters most.
  SceneSpec s = cleanScene({-1500, -2500, 2500}, {-300, 200, 0}, 420, 0.12, 480, 384);
  const std::vector<FieldMm> spots = {{-300, 200}, {400, 900}, {-1100, -300}, {600, -400}};
  for (size_t i = 0; i < spots.size(); ++i)
    s.robots.push_back({Team::Yellow, int(i), spots[i], 0.4 * i, 140, {}, 0});
  const Renderer r(s);
  const cv::Mat rad = r.renderRadiance(0, 0);
  const CameraModel cam(s.cameras[0].calib);
  for (const FieldMm& p : spots) {
    const auto want = cam.fieldToImage({p.x, p.y, 140});
    ASSERT_TRUE(want);
    ASSERT_GT(want->u, 10);
    ASSERT_LT(want->u, 470);
    double mass = 0;
    const ImagePx c = blueCentroid(rad, *want, 8, &mass);
    EXPECT_GT(mass, 250 * 4) << "blob not rendered at " << p.x << "," << p.y;
    EXPECT_NEAR(c.u, want->u, 0.3) << "robot at " << p.x << "," << p.y;
    EXPECT_NEAR(c.v, want->v, 0.3) << "robot at " << p.x << "," << p.y;
  }
}

// The ball's silhouette in a radiance image is centered where the camera
// model puts it. The shaded sphere's brightness is not symmetric, so the
// silhouette is compared: the carpet gives green 100 * (1 - coverage) and
// the specular highlight adds the same to red and green.
void expectBallSilhouetteAt(const cv::Mat& rad, ImagePx want) {
  double sw = 0, su = 0, sv = 0;
  for (int v = int(want.v) - 8; v <= int(want.v) + 8; ++v)
    for (int u = int(want.u) - 8; u <= int(want.u) + 8; ++u) {
      const cv::Vec3f p = rad.at<cv::Vec3f>(v, u);
      const double cover = 1 - (p[1] - p[2]) / 100.0;
      sw += cover, su += cover * u, sv += cover * v;
    }
  EXPECT_NEAR(su / sw, want.u, 0.3);
  EXPECT_NEAR(sv / sw, want.v, 0.3);
}

TEST(SynthRender, BallCenterWhereTheCameraModelSays) {
  SceneSpec s = cleanScene({0, 0, 3000}, {0, 0, 0}, 600, 0.05);
  s.ball.present = true;
  s.ball.position = {-420, 310, 21.5};
  s.lighting.object_shadow = 0;
  const Renderer r(s);
  const RenderedFrame f = r.render(0, 0);
  ASSERT_EQ(f.truth.balls_size(), 1);
  const auto want = CameraModel(s.cameras[0].calib).fieldToImage({-420, 310, 21.5});
  ASSERT_TRUE(want);
  EXPECT_NEAR(f.truth.balls(0).pixel_x(), want->u, 1e-3);
  EXPECT_FLOAT_EQ(f.truth.balls(0).z(), 21.5f);
  expectBallSilhouetteAt(r.renderRadiance(0, 0), *want);
}

TEST(SynthRender, MovingRobotTruthIsMidExposureAndMatchesTheBlurredBlob) {
  SceneSpec s = cleanScene({0, 0, 3000}, {0, 0, 0}, 600, 0.0);
  s.robots.push_back({Team::Blue, 2, {-300, 100}, 0, 140, {2000, -1000}, 3.0});
  s.fps = 50;
  s.frames = 4;
  s.motion_blur = true;
  s.motion_blur_samples = 9;
  s.lighting.exposure_time = 0.01;
  const Renderer r(s);
  const RenderedFrame f = r.render(3, 0);
  ASSERT_EQ(f.truth.robots_blue_size(), 1);
  const auto& t = f.truth.robots_blue(0);
  EXPECT_NEAR(t.x(), -300 + 2000 * 0.06, 1e-3);
  EXPECT_NEAR(t.y(), 100 - 1000 * 0.06, 1e-3);
  EXPECT_NEAR(t.orientation(), 0.18, 1e-5);
  EXPECT_DOUBLE_EQ(f.truth.t_capture(), 0.06);
  EXPECT_EQ(f.truth.frame_number(), 3u);
  // Constant velocity: the blur streak is centered on the mid-exposure position.
  const ImagePx c = blueCentroid(f.image, {t.pixel_x(), t.pixel_y()}, 14);
  EXPECT_NEAR(c.u, t.pixel_x(), 0.3);
  EXPECT_NEAR(c.v, t.pixel_y(), 0.3);
}

// A ball rolling into a wall bounces back with the restitution, a kick
// turns it; truth is the mid-exposure position and the rendered ball is
// there.
TEST(SynthRender, BouncingAndKickedBallTruthMatchesTheRender) {
  SceneSpec s = cleanScene({0, 0, 3000}, {0, 0, 0}, 600, 0.0);
  s.field.field_length = 1000;  // walls at x = +-600, y = +-500
  s.field.field_width = 800;
  s.field.boundary_width = 100;
  s.field.boundary_width_goal_line = 100;
  s.field.goal_width = 300;
  s.field.generateMarkings();
  s.materials.wall = {0, 100, 0};  // only the ball differs from the carpet
  s.materials.goal = {0, 100, 0};
  s.ball.present = true;
  s.ball.position = {400, 0, 21.5};
  s.ball.velocity = {3000, 0, 0};
  s.ball.wall_restitution = 0.9;
  s.ball.kicks = {{0.12, {0, 2000, 0}}};
  s.fps = 60;
  s.frames = 10;
  const Renderer r(s);
  // Hits the wall (center at 600 - 21.5) at t = 178.5 / 3000 s.
  const double t_hit = 178.5 / 3000;
  struct Want {
    int frame;
    double x, y;
  };
  const Want wants[] = {{3, 400 + 3000 * 0.05, 0},
                        {6, 578.5 - 2700 * (0.1 - t_hit), 0},
                        {9, 578.5 - 2700 * (0.12 - t_hit), 2000 * 0.03}};
  const CameraModel cam(s.cameras[0].calib);
  for (const Want& w : wants) {
    SCOPED_TRACE(w.frame);
    const RenderedFrame f = r.render(w.frame, 0);
    ASSERT_EQ(f.truth.balls_size(), 1);
    EXPECT_NEAR(f.truth.balls(0).x(), w.x, 1e-3);
    EXPECT_NEAR(f.truth.balls(0).y(), w.y, 1e-3);
    const auto want = cam.fieldToImage({w.x, w.y, 21.5});
    ASSERT_TRUE(want);
    expectBallSilhouetteAt(r.renderRadiance(w.frame / s.fps, 0), *want);
  }
}

TEST(SynthRender, BayerSitesFollowRGGB) {
  SceneSpec s = cleanScene({0, 0, 3000}, {0, 0, 0}, 600, 0.0, 64, 48);
  // Everything pure red.
  SceneMaterials& m = s.materials;
  for (Rgb* c : {&m.carpet, &m.line, &m.wall, &m.goal, &m.floor, &m.background, &m.robot_top,
                 &m.robot_body, &m.yellow, &m.blue, &m.green, &m.pink, &m.ball})
    *c = {200, 0, 0};
  s.bayer = true;
  const RenderedFrame f = Renderer(s).render(0, 0);
  ASSERT_EQ(f.image.type(), CV_8UC1);
  for (int v = 0; v < f.image.rows; ++v)
    for (int u = 0; u < f.image.cols; ++u) {
      const int value = f.image.at<uint8_t>(v, u);
      if (v % 2 == 0 && u % 2 == 0)
        EXPECT_EQ(value, 200) << u << "," << v;
      else
        EXPECT_EQ(value, 0) << u << "," << v;
    }
  // Pure blue lands only on (odd, odd).
  for (Rgb* c : {&m.carpet, &m.line, &m.wall, &m.goal, &m.floor, &m.background}) *c = {0, 0, 150};
  const RenderedFrame b = Renderer(s).render(0, 0);
  EXPECT_EQ(b.image.at<uint8_t>(1, 1), 150);
  EXPECT_EQ(b.image.at<uint8_t>(0, 0), 0);
  EXPECT_EQ(b.image.at<uint8_t>(0, 1), 0);
  EXPECT_EQ(b.image.at<uint8_t>(1, 0), 0);
}

TEST(SynthRender, BayerPixelsSampleTheirOwnCenters) {
  // A sharp vertical color edge: the mosaic must equal the RGB render's
  // channel at each site, not a value shared by a 2x2 cell.
  SceneSpec s = cleanScene({0, 0, 3000}, {0, 0, 0}, 600, 0.0, 64, 48);
  s.materials.carpet = {180, 140, 100};
  const cv::Mat rgb = Renderer(s).render(0, 0).image;
  s.bayer = true;
  const cv::Mat bayer = Renderer(s).render(0, 0).image;
  for (int v = 0; v < bayer.rows; ++v)
    for (int u = 0; u < bayer.cols; ++u) {
      const int ch = (v % 2 == 0) ? (u % 2 == 0 ? 2 : 1) : (u % 2 == 0 ? 1 : 0);
      ASSERT_EQ(bayer.at<uint8_t>(v, u), rgb.at<cv::Vec3b>(v, u)[ch]) << u << "," << v;
    }
}

TEST(SynthRender, BayerLayoutsPutEachColorOnItsSite) {
  SceneSpec s = cleanScene({0, 0, 3000}, {0, 0, 0}, 600, 0.0, 64, 48);
  s.materials.carpet = {180, 140, 100};
  const cv::Mat rgb = Renderer(s).render(0, 0).image;
  s.bayer = true;
  // Red site (x, y) in the 2x2 cell; blue diagonally opposite.
  const struct {
    BayerLayout layout;
    int rx, ry;
  } cases[] = {{BayerLayout::RGGB, 0, 0}, {BayerLayout::GRBG, 1, 0}, {BayerLayout::GBRG, 0, 1},
               {BayerLayout::BGGR, 1, 1}};
  for (const auto& c : cases) {
    s.bayer_layout = c.layout;
    const cv::Mat bayer = Renderer(s).render(0, 0).image;
    for (int v = 0; v < bayer.rows; ++v)
      for (int u = 0; u < bayer.cols; ++u) {
        const bool xr = u % 2 == c.rx, yr = v % 2 == c.ry;
        const int ch = xr && yr ? 2 : (!xr && !yr ? 0 : 1);
        ASSERT_EQ(bayer.at<uint8_t>(v, u), rgb.at<cv::Vec3b>(v, u)[ch])
            << "layout " << int(c.layout) << " at " << u << "," << v;
      }
  }
}

TEST(SynthRender, VignettingDarkensTheCornersByItsAmount) {
  cv::Mat map(101, 201, CV_32F, cv::Scalar(1.0f));
  applyVignetting(map, 0.6);
  EXPECT_NEAR(map.at<float>(50, 100), 1.0, 1e-6);
  EXPECT_NEAR(map.at<float>(0, 0), 0.4, 1e-5);
  EXPECT_NEAR(map.at<float>(100, 200), 0.4, 1e-5);
  EXPECT_GT(map.at<float>(50, 0), map.at<float>(0, 0));
  // Through the renderer: a uniform carpet is darker in the corner.
  SceneSpec s = cleanScene({0, 0, 3000}, {0, 0, 0}, 600, 0.0, 64, 48);
  s.lighting.vignetting = 0.5;
  const cv::Mat img = Renderer(s).render(0, 0).image;
  EXPECT_LT(img.at<cv::Vec3b>(0, 0)[1], 0.7 * img.at<cv::Vec3b>(24, 32)[1]);
}

TEST(SynthRender, TruthListsOnlyObjectsInsideTheImage) {
  SceneSpec s = cleanScene({0, 0, 3000}, {0, 0, 0}, 600, 0.0);
  // 320x256 at f=600 from 2860 mm (robot tops): about +-760 x +-610 mm.
  s.robots.push_back({Team::Yellow, 1, {100, 100}, 0, 140, {}, 0});   // inside
  s.robots.push_back({Team::Yellow, 2, {2000, 0}, 0, 140, {}, 0});    // outside
  s.robots.push_back({Team::Blue, 3, {-600, -400}, 0, 140, {}, 0});   // inside
  s.robots.push_back({Team::Blue, 4, {0, -1500}, 0, 140, {}, 0});     // outside
  s.ball.present = true;
  s.ball.position = {1500, 1500, 21.5};  // outside
  const Renderer r(s);
  const auto t = r.truth(0, 0);
  ASSERT_EQ(t.robots_yellow_size(), 1);
  EXPECT_EQ(t.robots_yellow(0).robot_id(), 1u);
  ASSERT_EQ(t.robots_blue_size(), 1);
  EXPECT_EQ(t.robots_blue(0).robot_id(), 3u);
  EXPECT_EQ(t.balls_size(), 0);
  EXPECT_EQ(t.camera_id(), 0u);
  for (const auto& rb : t.robots_yellow()) {
    EXPECT_GE(rb.pixel_x(), -0.5);
    EXPECT_LT(rb.pixel_x(), 319.5);
    EXPECT_FLOAT_EQ(rb.height(), 140);
    EXPECT_FLOAT_EQ(rb.confidence(), 1);
  }
}

TEST(SynthRender, DeterministicForASeed) {
  SceneSpec s = presetScene("top_down_div_b_half");
  scaleImages(s, 0.125);
  const cv::Mat a = Renderer(s).render(0, 0).image;
  const cv::Mat b = Renderer(s).render(0, 0).image;
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0);
  s.seed += 1;
  const cv::Mat c = Renderer(s).render(0, 0).image;
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1), 0);
  // Presets place the same robots every time.
  EXPECT_EQ(toCanonicalJson(Renderer(presetScene("top_down_div_b_half")).truth(0, 0)),
            toCanonicalJson(Renderer(presetScene("top_down_div_b_half")).truth(0, 0)));
}

TEST(SynthRender, ScaledPresetKeepsTheViewAndSubPixelTruth) {
  SceneSpec big = presetScene("top_down_div_b_half");
  SceneSpec small = big;
  scaleImages(small, 0.25);
  const auto tb = Renderer(big).truth(0, 0), ts = Renderer(small).truth(0, 0);
  ASSERT_EQ(tb.robots_yellow_size(), ts.robots_yellow_size());
  for (int i = 0; i < tb.robots_yellow_size(); ++i) {
    EXPECT_NEAR((ts.robots_yellow(i).pixel_x() + 0.5) * 4 - 0.5, tb.robots_yellow(i).pixel_x(), 0.05);
    EXPECT_NEAR((ts.robots_yellow(i).pixel_y() + 0.5) * 4 - 0.5, tb.robots_yellow(i).pixel_y(), 0.05);
  }
}

TEST(SynthRender, FlickerChangesFrameBrightness) {
  SceneSpec s = cleanScene({0, 0, 3000}, {0, 0, 0}, 600, 0.0, 64, 48);
  s.fps = 60;
  s.lighting.flicker_amplitude = 0.2;
  s.lighting.flicker_frequency = 100;
  s.lighting.exposure_time = 0.001;
  const Renderer r(s);
  std::vector<double> means;
  for (int f = 0; f < 3; ++f) means.push_back(cv::mean(r.render(f, 0).image)[1]);
  // Frames 0, 1, 2 sample sin(2 pi 100 t) at t = 0, 1/60, 2/60: 0, -0.87, +0.87.
  const double sinc = std::sin(kPi * 100 * 0.001) / (kPi * 100 * 0.001);
  EXPECT_NEAR(means[1] / means[0], 1 + 0.2 * std::sin(2 * kPi * 100 / 60.0) * sinc, 0.02);
  EXPECT_GT(means[2], means[0] * 1.1);
  EXPECT_LT(means[1], means[0] * 0.9);
}

TEST(SynthRender, WriteSceneFilesAndGeometryRoundTrip) {
  const TempDir tmp("dv_synth_test");
  const fs::path& dir = tmp.path();
  SceneSpec s = presetScene("two_cameras_overlap");
  scaleImages(s, 0.0625);
  s.frames = 2;
  s.write_png = true;
  writeScene(s, dir.string());
  for (int f = 0; f < 2; ++f)
    for (int cam : {0, 1}) {
      char name[64];
      std::snprintf(name, sizeof name, "frame_%d_%05d", cam, f);
      EXPECT_TRUE(fs::exists(dir / (std::string(name) + ".pgm"))) << name;
      EXPECT_TRUE(fs::exists(dir / (std::string(name) + ".png"))) << name;
    }
  const Geometry g = loadGeometry((dir / "geometry.json").string());
  ASSERT_EQ(g.cameras.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const CameraCalibration& want = s.cameras[i].calib;
    const CameraCalibration& got = g.cameras[i];
    EXPECT_EQ(got.camera_id, want.camera_id);
    EXPECT_NEAR(got.focal_length, want.focal_length, 1e-3);
    EXPECT_NEAR(got.principal_point_x, want.principal_point_x, 1e-3);
    EXPECT_NEAR(got.principal_point_y, want.principal_point_y, 1e-3);
    EXPECT_NEAR(got.distortion, want.distortion, 1e-6);
    EXPECT_NEAR(got.q0, want.q0, 1e-6);
    EXPECT_NEAR(got.q3, want.q3, 1e-6);
    EXPECT_NEAR(got.tx, want.tx, 1e-2);
    EXPECT_NEAR(got.tz, want.tz, 1e-2);
    EXPECT_EQ(got.image_width, want.image_width);
    EXPECT_EQ(got.image_height, want.image_height);
  }
  EXPECT_EQ(g.field.field_length, s.field.field_length);
  // truth.jsonl: frames in order, camera by camera within a frame.
  std::ifstream in(dir / "truth.jsonl");
  std::string line;
  std::vector<std::pair<uint32_t, uint32_t>> order;
  while (std::getline(in, line)) {
    dv::ssl::SSL_DetectionFrame f;
    parseCanonicalJson(line, f, "truth.jsonl");
    order.push_back({f.frame_number(), f.camera_id()});
  }
  const std::vector<std::pair<uint32_t, uint32_t>> want = {{0, 0}, {0, 1}, {1, 0}, {1, 1}};
  EXPECT_EQ(order, want);
}

TEST(SynthRender, TwoCameraPresetSeesTheOverlapFromBoth) {
  const SceneSpec s = presetScene("two_cameras_overlap");
  const Renderer r(s);
  const auto a = r.truth(0, 0), b = r.truth(0, 1);
  auto has = [](const dv::ssl::SSL_DetectionFrame& f, uint32_t id) {
    for (const auto& x : f.robots_blue())
      if (x.robot_id() == id && std::abs(x.x() - 250) < 1) return true;
    return false;
  };
  EXPECT_TRUE(has(a, 1));
  EXPECT_TRUE(has(b, 1));
  EXPECT_EQ(a.balls_size(), 1);
  EXPECT_EQ(b.balls_size(), 1);
}

TEST(SynthRender, SideViewSeesTheHorizon) {
  SceneSpec s = presetScene("side_view");
  scaleImages(s, 0.0625);
  const cv::Mat rad = Renderer(s).renderRadiance(0, 0);
  const Rgb bg = s.materials.background;
  // Top row: rays above the horizon hit nothing; bottom row: carpet.
  for (int u = 0; u < rad.cols; ++u) {
    const cv::Vec3f p = rad.at<cv::Vec3f>(0, u);
    EXPECT_FLOAT_EQ(p[0], float(bg.b));
    EXPECT_FLOAT_EQ(p[2], float(bg.r));
  }
  const cv::Vec3f bottom = rad.at<cv::Vec3f>(rad.rows - 1, rad.cols / 2);
  EXPECT_GT(bottom[1], bottom[2]);  // green carpet
}

TEST(SynthRender, UnevenLightSpansTheRatioAcrossTheImage) {
  const cv::Mat map = unevenLightMap(200, 100, 3.0, 0.5);
  double lo = 0, hi = 0;
  cv::minMaxLoc(map, &lo, &hi);
  EXPECT_NEAR(hi / lo, 3.0, 1e-4);
  EXPECT_GT(map.at<float>(99, 199), map.at<float>(0, 0));  // brighter along +u, +v
  SceneLighting l;
  l.flicker_amplitude = 0.1;
  l.flicker_frequency = 100;
  l.exposure_time = 0.01;  // one full flicker period: averages out
  EXPECT_NEAR(flickerGain(l, 0.0025), 1.0, 1e-9);
}

}  // namespace
}  // namespace dv

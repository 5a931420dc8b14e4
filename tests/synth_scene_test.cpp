// Scene files and presets: every shipped preset loads and renders; bad scene
// files and unknown presets give one InputError naming the file, the place
// and what is wrong, and `dotvision synth` turns them into exit code 2.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "core/error.h"
#include "temp_dir.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

std::string writeTemp(const std::string& name, const std::string& text) {
  static const TempDir dir("dv_synth_scene_test");
  const fs::path p = dir.path() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

const char* kMinimal = R"(
name: tiny
cameras:
  - {id: 3, position: [0, 0, 3000], look_at: [0, 0, 0], focal_length: 300, size: [160, 128]}
robots:
  - {team: blue, id: 7, position: [100, -50], orientation: 1.0}
ball: {position: [-200, 100]}
)";

// The message of the InputError that loading `text` throws ("" if none).
std::string loadError(const std::string& name, const std::string& text) {
  const std::string path = writeTemp(name, text);
  try {
    loadScene(path);
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), path);
    return e.what();
  }
  return "";
}

TEST(SynthScene, MinimalSceneLoads) {
  const SceneSpec s = loadScene(writeTemp("minimal.yaml", kMinimal));
  EXPECT_EQ(s.name, "tiny");
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].calib.camera_id, 3u);
  EXPECT_EQ(s.cameras[0].calib.image_width, 160u);
  EXPECT_DOUBLE_EQ(s.cameras[0].calib.principal_point_x, 79.5);
  ASSERT_EQ(s.robots.size(), 1u);
  EXPECT_EQ(s.robots[0].team, Team::Blue);
  EXPECT_EQ(s.robots[0].id, 7);
  EXPECT_DOUBLE_EQ(s.ball.position.z, 21.5);  // resting by default
  EXPECT_TRUE(s.ball.present);
  // The camera looks straight down from 3 m: the field origin is at the
  // principal point.
  const auto px = CameraModel(s.cameras[0].calib).fieldToImage({0, 0, 0});
  ASSERT_TRUE(px);
  EXPECT_NEAR(px->u, 79.5, 1e-9);
  EXPECT_NEAR(px->v, 63.5, 1e-9);
}

// A camera may carry lens terms beyond the league's model; a wrong count is named.
TEST(SynthScene, CameraLensTerms) {
  std::string text = kMinimal;
  const std::string cam = "focal_length: 300,";
  text.insert(text.find(cam) + cam.size(), " lens: [-0.004, 0.0001, 0.0006, -0.0004],");
  const SceneSpec s = loadScene(writeTemp("lens.yaml", text));
  EXPECT_EQ(s.cameras[0].calib.lens, (LensTerms{-0.004, 0.0001, 0.0006, -0.0004}));
  std::string bad = kMinimal;
  bad.insert(bad.find(cam) + cam.size(), " lens: [-0.004, 0],");
  EXPECT_NE(loadError("bad_lens.yaml", bad).find("cameras[0].lens"), std::string::npos) << loadError("bad_lens.yaml", bad);
}

TEST(SynthScene, MalformedYamlNamesFileLineAndColumn) {
  const std::string msg = loadError("malformed.yaml", "name: x\ncameras: [\n  {id: 0,\n");
  EXPECT_NE(msg.find("malformed.yaml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line "), std::string::npos) << msg;
  EXPECT_NE(msg.find("malformed YAML"), std::string::npos) << msg;
}

TEST(SynthScene, WrongTypeNamesTheKeyAndPlace) {
  const std::string msg = loadError("wrong_type.yaml", std::string(kMinimal) + "fps: fast\n");
  EXPECT_NE(msg.find("wrong_type.yaml: line 8, column 6: fps: expected a number, got 'fast'"),
            std::string::npos)
      << msg;
  const std::string msg2 = loadError(
      "wrong_type2.yaml",
      "cameras:\n  - {position: [0, 0, x], look_at: [0, 0, 0], focal_length: 300, size: [16, 16]}\n");
  EXPECT_NE(msg2.find("line 2"), std::string::npos) << msg2;
  EXPECT_NE(msg2.find("cameras[0].position"), std::string::npos) << msg2;
  const std::string msg3 =
      loadError("wrong_type3.yaml", std::string(kMinimal) + "lighting: {white_balance: 1.2}\n");
  EXPECT_NE(msg3.find("lighting.white_balance: expected a list of 3 numbers"), std::string::npos)
      << msg3;
}

TEST(SynthScene, UnknownKeyIsNamed) {
  const std::string msg = loadError("unknown_key.yaml", std::string(kMinimal) + "fsp: 60\n");
  EXPECT_NE(msg.find("line 8, column 1: unknown key 'fsp' in scene"), std::string::npos) << msg;
  const std::string nested =
      loadError("unknown_nested.yaml", std::string(kMinimal) + "lighting:\n  exposur: 2\n");
  EXPECT_NE(nested.find("line 9, column 3: unknown key 'exposur' in lighting"), std::string::npos)
      << nested;
}

TEST(SynthScene, ImpossibleValuesAreRejected) {
  EXPECT_NE(loadError("bad_team.yaml",
                      "cameras:\n  - {position: [0, 0, 3000], look_at: [0, 0, 0], focal_length: 300, "
                      "size: [16, 16]}\nrobots:\n  - {team: red, id: 1, position: [0, 0]}\n")
                .find("unknown team 'red'"),
            std::string::npos);
  EXPECT_NE(loadError("bad_id.yaml",
                      "cameras:\n  - {position: [0, 0, 3000], look_at: [0, 0, 0], focal_length: 300, "
                      "size: [16, 16]}\nrobots:\n  - {team: blue, id: 16, position: [0, 0]}\n")
                .find("robots[0].id: 16 is outside [0, 15]"),
            std::string::npos);
  EXPECT_NE(loadError("no_cameras.yaml", "name: x\n").find("missing key 'cameras'"),
            std::string::npos);
  EXPECT_NE(loadError("empty.yaml", "").find("empty"), std::string::npos);
  EXPECT_NE(loadError("frames.yaml", std::string(kMinimal) + "frames: 0\n").find("frames: 0 is outside"),
            std::string::npos);
}

TEST(SynthScene, BallKicksAndRestitutionLoad) {
  // kMinimal with its ball line replaced.
  auto withBall = [](const std::string& ball) {
    std::string text = kMinimal;
    const std::string old = "ball: {position: [-200, 100]}";
    return text.replace(text.find(old), old.size(), ball);
  };
  const SceneSpec s = loadScene(writeTemp(
      "kicks.yaml", withBall("ball: {position: [0, 0], velocity: [1000, 0], wall_restitution: 0.5,\n"
                             "       kicks: [{t: 0.1, velocity: [0, -2000]}, {t: 0.3, velocity: [5, 5, 1]}]}")));
  EXPECT_DOUBLE_EQ(s.ball.wall_restitution, 0.5);
  ASSERT_EQ(s.ball.kicks.size(), 2u);
  EXPECT_DOUBLE_EQ(s.ball.kicks[0].t, 0.1);
  EXPECT_DOUBLE_EQ(s.ball.kicks[0].velocity.y, -2000);
  EXPECT_DOUBLE_EQ(s.ball.kicks[1].velocity.z, 1);
  const std::string order = loadError(
      "kick_order.yaml", withBall("ball: {kicks: [{t: 0.3, velocity: [1, 0]}, {t: 0.2, velocity: [1, 0]}]}"));
  EXPECT_NE(order.find("ball.kicks[1].t: kicks must be in increasing time"), std::string::npos)
      << order;
  const std::string restitution =
      loadError("restitution.yaml", withBall("ball: {wall_restitution: 1.5}"));
  EXPECT_NE(restitution.find("ball.wall_restitution: 1.5 is outside"), std::string::npos) << restitution;
}

// The motion preset's ball really moves at the speed it asks for: kicked near
// 6.5 m/s, bouncing off the walls and away from robots, never leaving the
// walls or touching a robot; robots move fast too.
TEST(SynthScene, MotionPresetBallReachesItsSpeedAndStaysInTheField) {
  const SceneSpec s = presetScene("motion_60fps_flicker");
  ASSERT_TRUE(s.ball.present);
  const FieldRect walls = s.field.withBoundary();
  const double r = s.field.ball_radius;
  const double duration = s.frames / s.fps, step = 0.0005;
  double fastest = 0, nearest_robot = 1e9;
  FieldPoint prev = ballPositionAt(s.ball, s.field, 0);
  for (double t = step; t <= duration; t += step) {
    const FieldPoint p = ballPositionAt(s.ball, s.field, t);
    fastest = std::max(fastest, std::hypot(p.x - prev.x, p.y - prev.y) / step);
    prev = p;
    ASSERT_GE(p.x, walls.x_min + r - 1e-6) << "t " << t;
    ASSERT_LE(p.x, walls.x_max - r + 1e-6) << "t " << t;
    ASSERT_GE(p.y, walls.y_min + r - 1e-6) << "t " << t;
    ASSERT_LE(p.y, walls.y_max - r + 1e-6) << "t " << t;
    for (const SceneRobot& rb : s.robots) {
      const FieldMm q = robotPositionAt(rb, t);
      nearest_robot = std::min(nearest_robot, std::hypot(p.x - q.x, p.y - q.y));
    }
  }
  EXPECT_GE(fastest, 6000);
  EXPECT_LE(fastest, 6500 + 1e-6);
  EXPECT_GE(nearest_robot, RobotPatternGeometry::kMaxRadius + r);
  double fastest_robot = 0;
  int moving = 0;
  for (const SceneRobot& rb : s.robots) {
    const double v = std::hypot(rb.velocity.x, rb.velocity.y);
    fastest_robot = std::max(fastest_robot, v);
    moving += v > 0;
  }
  EXPECT_GE(fastest_robot, 2500);
  EXPECT_GE(moving, int(s.robots.size()) / 2);
  // The same course for the same seed.
  const SceneSpec again = presetScene("motion_60fps_flicker");
  ASSERT_EQ(again.ball.kicks.size(), s.ball.kicks.size());
  EXPECT_EQ(ballPositionAt(again.ball, again.field, 0.7).x, ballPositionAt(s.ball, s.field, 0.7).x);
}

TEST(SynthScene, MutatedScenesGiveInputErrorsNeverCrashes) {
  // Every single-character deletion or replacement of a valid scene either
  // loads or throws InputError; nothing else escapes.
  const std::string base = std::string(kMinimal) +
                           "random_robots: {yellow: 2, blue: 2}\nlighting: {sun_patches: "
                           "[{center: [0, 0], radii: [100, 50]}]}\nfield: {division: a}\n";
  int errors = 0, loaded = 0;
  for (size_t i = 0; i < base.size(); ++i)
    for (const char* with : {"", ":", "[", "-", "x", "9", " ", "{"}) {
      const std::string text = base.substr(0, i) + with + base.substr(i + 1);
      try {
        sceneFromYaml(text, "mutant");
        ++loaded;
      } catch (const InputError& e) {
        EXPECT_EQ(e.source(), "mutant");
        ++errors;
      } catch (const std::exception& e) {
        ADD_FAILURE() << "not an InputError: " << e.what() << "\n" << text;
      }
    }
  EXPECT_GT(errors, 100);
  EXPECT_GT(loaded, 10);
}

TEST(SynthScene, MissingFileIsAnInputError) {
  const std::string path = "/nonexistent/dir/scene.yaml";
  try {
    loadScene(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), path);
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
  }
}

TEST(SynthScene, UnknownPresetListsTheKnownOnes) {
  try {
    presetScene("top_down_div_z");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.source(), "preset");
    EXPECT_NE(msg.find("unknown preset 'top_down_div_z'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("top_down_div_b_half"), std::string::npos) << msg;
  }
}

// The presets are built into the binary: the same scenes as the YAML files
// of the source tree, with no file read.
TEST(SynthScene, EmbeddedPresetsMatchTheSourceFiles) {
  const std::filesystem::path dir = std::filesystem::path(DV_SOURCE_DIR) / "config" / "scenes";
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".yaml") files.push_back(e.path().stem().string());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(presetNames(), files);
  for (const auto& n : files) {
    SCOPED_TRACE(n);
    const SceneSpec built_in = presetScene(n);
    const SceneSpec from_file = loadScene((dir / (n + ".yaml")).string());
    EXPECT_EQ(built_in.robots.size(), from_file.robots.size());
    EXPECT_EQ(built_in.seed, from_file.seed);
    EXPECT_EQ(built_in.cameras.size(), from_file.cameras.size());
  }
}

TEST(SynthScene, AllPresetsLoadAndRenderSmall) {
  const std::vector<std::string> want = {"blue_white_balance", "dark_noisy",
                                         "gray_carpet",        "motion_60fps_flicker",
                                         "side_view",          "top_down_div_b_half",
                                         "two_cameras_overlap", "uneven_light"};
  const auto names = presetNames();
  for (const auto& n : want)
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << "missing preset " << n;
  for (const auto& n : names) {
    SCOPED_TRACE(n);
    SceneSpec s = presetScene(n);
    EXPECT_EQ(s.name, n);
    scaleImages(s, 0.0625);
    const Renderer r(s);
    for (size_t c = 0; c < s.cameras.size(); ++c) {
      const RenderedFrame f = r.render(0, c);
      EXPECT_EQ(f.image.cols, int(s.cameras[c].calib.image_width));
      EXPECT_GT(f.truth.robots_yellow_size() + f.truth.robots_blue_size(), 0);
    }
  }
  const SceneSpec top = presetScene("top_down_div_b_half");
  EXPECT_EQ(top.robots.size(), 22u);
  EXPECT_EQ(top.cameras[0].calib.image_width, 2448u);
  const SceneSpec motion = presetScene("motion_60fps_flicker");
  EXPECT_EQ(motion.frames, 60);
  EXPECT_TRUE(motion.motion_blur);
  double fastest = 0;
  for (const auto& r : motion.robots) fastest = std::max(fastest, std::hypot(r.velocity.x, r.velocity.y));
  EXPECT_GT(fastest, 1000);
  EXPECT_LE(fastest, 3000);
}

TEST(SynthScene, RandomRobotsAreDistinctApartAndInView) {
  SceneSpec s = defaultScene();
  s.robots.clear();
  const auto robots = placeRandomRobots(s, 0, 11, 11, 42);
  ASSERT_EQ(robots.size(), 22u);
  const CameraModel cam(s.cameras[0].calib);
  for (size_t i = 0; i < robots.size(); ++i) {
    const auto px = cam.fieldToImage({robots[i].position.x, robots[i].position.y, robots[i].height});
    ASSERT_TRUE(px);
    EXPECT_GE(px->u, 0);
    EXPECT_LT(px->u, s.cameras[0].calib.image_width);
    for (size_t j = 0; j < i; ++j) {
      EXPECT_GE(std::hypot(robots[i].position.x - robots[j].position.x,
                           robots[i].position.y - robots[j].position.y),
                200);
      if (robots[i].team == robots[j].team) {
        EXPECT_NE(robots[i].id, robots[j].id);
      }
    }
  }
  const auto again = placeRandomRobots(s, 0, 11, 11, 42);
  EXPECT_EQ(again[5].position.x, robots[5].position.x);
}

TEST(SynthScene, RandomRobotsStayOutOfTheGoalWalls) {
  // A camera over one goal: no robot may stand in the goal's walls.
  SceneSpec s = defaultScene();
  s.cameras = {makeCamera(0, {-4400, 0, 3000}, {-4400, 0, 0}, 600, 0, {}, 640, 480, {-1, 0, 0})};
  s.ball.present = false;
  s.robots.clear();
  const double back = s.field.field_length / 2.0 + s.field.line_thickness / 2.0 + s.field.goal_depth;
  for (uint64_t seed = 1; seed <= 20; ++seed)
    for (const auto& r : placeRandomRobots(s, 0, 8, 8, seed, 180, 10)) {
      const bool in_goal_rows = std::abs(r.position.y) < s.field.goal_width / 2.0 + 90;
      if (in_goal_rows) {
        EXPECT_GE(r.position.x, -back + 90) << "seed " << seed;
      }
    }
}

TEST(SynthScene, BayerKeyTakesALayoutOrABoolean) {
  const std::string head = "cameras: [{id: 0, position: [0, 0, 4000], look_at: [0, 0, 0], focal_length: 500, size: [64, 48]}]\n";
  EXPECT_EQ(sceneFromYaml(head + "bayer: gbrg\n", "t").bayer_layout, BayerLayout::GBRG);
  EXPECT_TRUE(sceneFromYaml(head + "bayer: bggr\n", "t").bayer);
  EXPECT_FALSE(sceneFromYaml(head + "bayer: false\n", "t").bayer);
  EXPECT_EQ(sceneFromYaml(head + "bayer: true\n", "t").bayer_layout, BayerLayout::RGGB);
  EXPECT_THROW(sceneFromYaml(head + "bayer: rgbg\n", "t"), InputError);
  EXPECT_DOUBLE_EQ(sceneFromYaml(head + "lighting: {vignetting: 0.4}\n", "t").lighting.vignetting, 0.4);
  EXPECT_THROW(sceneFromYaml(head + "lighting: {vignetting: 1.5}\n", "t"), InputError);
}

// A camera that streams JPEG: the frame written is the JPEG file the
// renderer's image was decoded from, so `run` on the folder reads exactly
// the pixels the in-memory tests see; JPEG needs RGB frames.
TEST(SynthScene, JpegFramesAreWrittenAsDecoded) {
  const std::string head = "cameras: [{id: 0, position: [0, 0, 4000], look_at: [0, 0, 0], focal_length: 500, size: [64, 48]}]\n";
  EXPECT_EQ(sceneFromYaml(head + "bayer: false\njpeg_quality: 75\n", "t").jpeg_quality, 75);
  try {
    sceneFromYaml(head + "jpeg_quality: 75\n", "t");
    ADD_FAILURE() << "JPEG of a Bayer mosaic accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("set bayer: false"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sceneFromYaml(head + "bayer: false\njpeg_quality: 101\n", "t"), InputError);

  SceneSpec spec = sceneFromYaml(std::string(kMinimal) + "bayer: false\njpeg_quality: 60\n", "t");
  const fs::path out = fs::path(writeTemp("jpeg_marker", "")).parent_path() / "jpeg_out";
  writeScene(spec, out.string());
  const cv::Mat read = cv::imread((out / "frame_3_00000.jpg").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(read.empty());
  EXPECT_FALSE(fs::exists(out / "frame_3_00000.png"));
  const cv::Mat decoded = Renderer(spec).render(0, 0).image;
  EXPECT_EQ(cv::norm(read, decoded, cv::NORM_INF), 0);
  spec.jpeg_quality = 0;
  EXPECT_GT(cv::norm(Renderer(spec).render(0, 0).image, decoded, cv::NORM_INF), 0);
}

// Runs the CLI; returns its exit code and stderr.
int runCli(const std::string& args, std::string& err) {
  const std::string err_path = writeTemp("cli_stderr.txt", "");
  const std::string cmd = std::string(DV_CLI_PATH) + " " + args + " >/dev/null 2>" + err_path;
  const int status = std::system(cmd.c_str());
  std::ifstream in(err_path);
  err.assign(std::istreambuf_iterator<char>(in), {});
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(SynthScene, CliExitsTwoWithOneLineForBadInput) {
  std::string err;
  const std::string bad = writeTemp("cli_bad.yaml", std::string(kMinimal) + "fsp: 60\n");
  EXPECT_EQ(runCli("synth " + bad + " --out " + writeTemp("out_a", ""), err), 2);
  EXPECT_NE(err.find("unknown key 'fsp'"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_EQ(runCli("synth --preset nope --out /tmp/dv_synth_never", err), 2);
  EXPECT_NE(err.find("unknown preset 'nope'"), std::string::npos) << err;
  EXPECT_EQ(runCli("synth /nonexistent.yaml --out /tmp/dv_synth_never", err), 2);
  EXPECT_NE(err.find("/nonexistent.yaml"), std::string::npos) << err;
  EXPECT_EQ(runCli("synth " + bad, err), 2);  // no --out
}

TEST(SynthScene, CliRendersAScene) {
  const std::string scene = writeTemp("cli_ok.yaml", std::string(kMinimal) + "frames: 2\npng: true\n");
  const fs::path out = fs::path(writeTemp("cli_ok_marker", "")).parent_path() / "cli_out";
  std::string err;
  ASSERT_EQ(runCli("synth " + scene + " --out " + out.string() + " --frames 1", err), 0) << err;
  EXPECT_TRUE(fs::exists(out / "frame_3_00000.pgm"));
  EXPECT_TRUE(fs::exists(out / "frame_3_00000.png"));
  EXPECT_FALSE(fs::exists(out / "frame_3_00001.pgm"));  // --frames 1
  EXPECT_TRUE(fs::exists(out / "geometry.json"));
  EXPECT_TRUE(fs::exists(out / "truth.jsonl"));
}

// Clutter (a hand, a shoe): a box in the scene that is seen, robots placed
// clear of it, and a box that is not one refused with its place.
TEST(SynthScene, ClutterBoxesAreSeenKeptClearOfAndChecked) {
  const std::string head = "cameras: [{id: 0, position: [0, 0, 4000], look_at: [0, 0, 0], focal_length: 60, size: [64, 48]}]\n";
  const SceneSpec s = sceneFromYaml(head + "clutter: [{min: [-200, -200, 0], max: [200, 200, 300], color: [230, 180, 150]}]\n", "t");
  ASSERT_EQ(s.clutter.size(), 1u);
  SceneSpec bare = s;
  bare.clutter.clear();
  const cv::Mat with = Renderer(s).render(0, 0).image, without = Renderer(bare).render(0, 0).image;
  EXPECT_GT(cv::norm(with, without, cv::NORM_L1), 1000) << "the box is in the camera's view";
  for (const SceneRobot& r : placeRandomRobots(s, 0, 3, 3, 5, 200, 2))
    EXPECT_GT(std::max(std::abs(r.position.x), std::abs(r.position.y)), 200 + 100 + 30 - 1) << "a robot under the box";
  try {
    sceneFromYaml(head + "clutter:\n  - {min: [0, 0, 0], max: [10, -10, 5], color: [1, 2, 3]}\n", "t");
    ADD_FAILURE() << "an inside-out box accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("clutter[0]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sceneFromYaml(head + "clutter: [{min: [0, 0, 0], max: [1, 1, 1]}]\n", "t"), InputError);
  EXPECT_THROW(sceneFromYaml(head + "clutter: [{min: [0, 0, 0], max: [1, 1, 1], color: [1, 2, 3], size: 2}]\n", "t"), InputError);
}

}  // namespace
}  // namespace dv

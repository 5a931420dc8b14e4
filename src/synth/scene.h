#pragma once
// What the synthetic renderer draws: cameras, field, robots, ball, materials,
// lighting and sensor effects of one scene (a single frame or a motion
// sequence). Scenes come from YAML files (see config/scenes/) or from the
// shipped presets; everything is deterministic for the scene's seed.
// Units: millimetres, radians, seconds; colors are 0..255 per channel as the
// sensor would read them under unit light, exposure and white balance.
#include <cstdint>
#include <string>
#include <vector>

#include "core/units.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "geometry/robot_pattern.h"

namespace dv {

// Where the color sites of a Bayer mosaic lie, named by the first 2x2 cell
// read row by row (RGGB: red at even row and even column).
enum class BayerLayout { RGGB, GRBG, GBRG, BGGR };

struct Rgb {
  double r = 0, g = 0, b = 0;
};

struct SceneCamera {
  CameraCalibration calib;  // image_width / image_height are set
};

// A camera at `position` looking at `look_at` (field mm). The principal point
// is the image center ((w-1)/2, (h-1)/2) plus `principal_offset` (px).
// `up` is the field direction that appears up in the image; the zero vector
// means field +z, or field +y for cameras looking (nearly) straight down.
SceneCamera makeCamera(uint32_t id, const FieldPoint& position, const FieldPoint& look_at,
                       double focal_length, double distortion, ImagePx principal_offset,
                       uint32_t width, uint32_t height, const FieldPoint& up = {});

struct SceneRobot {
  Team team = Team::Yellow;
  int id = 0;                   // pattern id 0..15
  FieldMm position;             // center blob, at t = 0
  double orientation = 0;       // rad, front direction, at t = 0
  double height = 140;          // mm, top plane (where the pattern lies)
  FieldMm velocity;             // mm/s
  double angular_velocity = 0;  // rad/s
};

// The ball's velocity from time `t` on: a kick, or a deflection off a robot.
struct BallKick {
  double t = 0;         // s
  FieldPoint velocity;  // mm/s
};

// The ball rolls straight (no friction) between kicks and bounces off the
// field walls (field.withBoundary()), keeping `wall_restitution` of its
// speed toward the wall. Before t = 0 it rolls on its initial velocity.
struct SceneBall {
  FieldPoint position{0, 0, 21.5};  // center, at t = 0; z = 21.5 resting
  FieldPoint velocity;              // mm/s, at t = 0
  std::vector<BallKick> kicks;      // in time order, t > 0
  double wall_restitution = 0.9;
  bool present = true;
};

// An elliptic patch of light (gain > 1, sun through a window) or shadow
// (gain < 1) on the field, with a soft edge.
struct LightPatch {
  FieldMm center;
  double radius_x = 500, radius_y = 300;  // mm, semi-axes
  double angle = 0;                       // rad, of the x semi-axis
  double gain = 1.8;                      // light multiplier inside
  double softness = 0.3;                  // edge width as a fraction of the radii
};

struct SceneLighting {
  double exposure = 1.0;  // overall brightness multiplier (exposure x gain)
  Rgb white_balance{1, 1, 1};  // per-channel gains applied by the camera
  // The camera's color processing after the gains: saturation mixes each
  // color with its luma (0 = gray, 1 = unchanged, > 1 more vivid); gamma
  // maps v -> 255 (v / 255)^gamma (1 = linear). Both 1: skipped.
  double saturation = 1.0;
  double gamma = 1.0;
  // Smooth brightness gradient across the image: brightest / darkest = ratio,
  // increasing along image direction `uneven_direction` (rad, 0 = +u).
  double uneven_ratio = 1.0;
  double uneven_direction = 0;
  // Lens vignetting: brightness falls with the squared distance from the
  // image center to 1 - vignetting at the corners (0 = none).
  double vignetting = 0;
  std::vector<LightPatch> sun_patches;  // gain > 1
  std::vector<LightPatch> shadows;      // gain < 1
  // Soft contact shadows that robots and the ball cast on the carpet (0..1).
  double object_shadow = 0.45;
  // Mains flicker: brightness x (1 + amplitude sin(2 pi f t)), averaged over
  // the exposure time.
  double flicker_amplitude = 0;
  double flicker_frequency = 100;  // Hz
  double exposure_time = 0.004;    // s, shutter open time (motion blur, flicker)
};

struct SceneMaterials {
  Rgb carpet{40, 110, 50};
  double carpet_texture = 0.12;  // relative brightness variation of the carpet
  Rgb line{235, 235, 235};
  Rgb wall{25, 25, 28};
  Rgb goal{230, 230, 230};
  Rgb floor{90, 90, 95};          // outside the walls
  Rgb background{60, 60, 70};     // rays that hit nothing (hall, horizon)
  Rgb robot_top{22, 22, 22};
  Rgb robot_body{35, 35, 38};
  Rgb yellow{230, 210, 40};
  Rgb blue{40, 80, 200};
  Rgb green{60, 200, 80};
  Rgb pink{240, 90, 180};
  Rgb ball{255, 120, 20};
};

// Something on or over the field that is neither robot nor ball: a hand
// placing a robot, a shoe by the wall, a cable, a bag (an axis-aligned box,
// shaded like the walls).
struct SceneBox {
  FieldPoint min, max;  // mm, corners
  Rgb color;
};

struct SceneSpec {
  std::string name = "scene";
  uint64_t seed = 1;
  FieldModel field = FieldModel::divisionB();
  std::vector<SceneCamera> cameras;
  std::vector<SceneRobot> robots;
  SceneBall ball;
  SceneMaterials materials;
  SceneLighting lighting;
  std::vector<SceneBox> clutter;
  double noise_sigma = 1.5;   // 8-bit levels, read noise
  double shot_noise = 0.05;   // variance per level of signal (Poisson-like)
  double lens_blur_px = 0.5;  // Gaussian sigma in pixels, 0 = sharp
  int frames = 1;
  double fps = 60;
  bool motion_blur = false;
  int motion_blur_samples = 5;  // sub-frame renders averaged per frame
  bool bayer = true;            // write 8-bit Bayer PGM frames
  BayerLayout bayer_layout = BayerLayout::RGGB;
  bool write_png = false;       // write PNG RGB frames as well
  // RGB frames (bayer false) pass through JPEG at this quality, as from a
  // camera that streams JPEG (4:2:0 chroma, block artefacts); 0 = lossless.
  int jpeg_quality = 0;
  int antialias = 2;            // samples per pixel axis
};

// Reads a scene YAML file. Throws InputError(path, "line L, column C: ...")
// for malformed YAML, wrong types, unknown keys (named) and impossible values;
// InputError(path, "cannot open ...") for a missing file.
SceneSpec loadScene(const std::string& path);
// The same from YAML text; `source` names the text in errors.
SceneSpec sceneFromYaml(const std::string& text, const std::string& source);

// The shipped presets (config/scenes/<name>.yaml) by name. Throws
// InputError("preset", "unknown preset 'x' (known: ...)").
SceneSpec presetScene(const std::string& name);
std::vector<std::string> presetNames();
// Where the presets are read from: $DV_SCENES_DIR when set, else empty: the
// copies of config/scenes/*.yaml built into the binary.
std::string presetDirectory();

// The built-in scene `dotvision run` uses when no camera is configured: one
// top-down camera over a Division B half field, 1224x1024 Bayer, 6+6 robots
// and a ball, a few frames with motion.
SceneSpec defaultScene();

// Places `yellow` + `blue` robots with random distinct ids, at least
// `min_distance` mm apart (and from the ball and the scene's own robots, whose
// ids they do not reuse; clear of the clutter's footprints), inside the walls
// and clear of the goals' walls, in camera
// `camera_index`'s view (center blob at least `margin_px` inside the image),
// with random orientations. Returns only the new robots. Deterministic for
// `seed`. Throws
// std::invalid_argument when the robots do not fit.
std::vector<SceneRobot> placeRandomRobots(const SceneSpec& scene, size_t camera_index,
                                          int yellow, int blue, uint64_t seed,
                                          double min_distance = 200, double margin_px = 40);

// Gives every robot a random velocity (speed between max_speed / 4 and
// max_speed mm/s, any direction) and angular velocity (up to
// max_angular_speed rad/s) such that over `duration` seconds no two robots
// come closer than 200 mm and all stay inside the walls; where no such
// motion is found, the robot stands. The ball is kicked at t = 0 with a
// speed between 0.9 and 1 x ball_max_speed, bounces off the walls, and is
// kicked again (0.5 to 1 x ball_max_speed, away from the robot) wherever it
// would touch a robot. Deterministic for `seed`.
void assignRandomMotion(SceneSpec& scene, double max_speed, double max_angular_speed,
                        double ball_max_speed, double duration, uint64_t seed);

// Scales every camera's image by `factor` (focal length and principal point
// with it, pixel centers at integer coordinates), e.g. to render a preset
// small in a test. The view stays the same.
void scaleImages(SceneSpec& scene, double factor);

// Position and orientation of a robot at time t (constant velocity).
FieldMm robotPositionAt(const SceneRobot& r, double t);
double robotOrientationAt(const SceneRobot& r, double t);
// The ball's center and velocity at time t, with its kicks and wall bounces
// inside `field`'s walls.
struct BallState {
  FieldPoint position;
  FieldPoint velocity;
};
BallState ballStateAt(const SceneBall& b, const FieldModel& field, double t);
FieldPoint ballPositionAt(const SceneBall& b, const FieldModel& field, double t);
// Whether the ball moves at any time (initial velocity or a kick).
bool ballMoves(const SceneBall& b);

}  // namespace dv

// Color conditions a venue brings, one at a time on the top-down half field
// (11 + 11 robots at random ids and a ball, each frame alone, shipped
// defaults): global color casts on both axes of the white balance, saturation
// and gamma of the camera's color processing, over-exposure with clipped
// channels, and the spread of marker and ball shades teams and the league
// actually use. The class colors must come from the frame, so every one of
// these holds with the same defaults. CI runs one placement at 1224 x 1024;
// DV_SCENE_FULL=1 runs 4 placements at both sizes and prints the table.
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <vector>

#include "scene_conditions.h"

namespace dv {
namespace {

using namespace dv::test;

// A focused test's placements of one condition (half: 1224 x 1024, else
// 2448 x 2048), each alone at 1.000 in every column the table reports.
void expectHeldAt(const Condition& c, std::initializer_list<int> placements, bool half) {
  for (int k : placements) {
    SceneScore s;
    score(conditionScene(c, k, half), 1, true, s);
    printRow(c.name, half ? "1224x1024" : "2448x2048", s);
    SCOPED_TRACE(std::string(c.name) + " placement " + std::to_string(k));
    EXPECT_EQ(s.recall(), 1.0);
    EXPECT_EQ(s.precision(), 1.0);
    EXPECT_EQ(s.idAccuracy(), 1.0);
    EXPECT_EQ(s.ballRecall(), 1.0);
    EXPECT_EQ(s.ballPrecision(), 1.0);
  }
}

// Tungsten with a sun patch (1.8) over the ball.
void tungstenSunOverTheBall(SceneSpec& s, int) {
  cast(s, kTungsten);
  s.lighting.sun_patches = {{{-1500, 900}, 800, 500, 0.2, 1.8, 0.25}};
  s.lighting.shadows = {{{-3000, -800}, 900, 500, -0.4, 0.45, 0.3}};
  s.lighting.vignetting = 0.5;
}

// A brighter sun patch (2.0) over a lighter ball under a desaturated cold
// LED cast, with lemon centers: the ball clips in two channels.
void coldSunOverThePaleBallLemon(SceneSpec& s, int) {
  cast(s, kColdLed, 0.6);
  s.materials.yellow = {240, 240, 60};
  s.materials.ball = {255, 150, 40};
  s.lighting.sun_patches = {{{-1500, 600}, 600, 600, 0.0, 2.0, 0.2}};
}

// Drawn at random (scripts/random_venues.py 57 --extreme): tungsten at
// exposure 1.4, saturation 0.4, lemon and navy centers, magenta and teal dots.
void tungstenExposedWashedLemonNavy(SceneSpec& s, int) {
  cast(s, {1.56, 1.04, 0.65}, 0.42, 1.11);
  s.lighting.exposure = 1.39;
  s.lighting.uneven_ratio = 1.58;
  s.lighting.uneven_direction = 2.98;
  s.materials.pink = {239, 76, 171};
  s.materials.green = {44, 175, 130};
  s.materials.yellow = {240, 239, 78};
  s.materials.blue = {39, 74, 159};
  s.materials.ball = {247, 94, 20};
}

// Drawn at random (scripts/random_venues.py 301 420, #314): a warm cast
// at saturation 0.4 and gamma 1.23, a sun patch of 1.67 over the ball.
void warmDesaturatedSunOverTheBall(SceneSpec& s, int) {
  cast(s, {1.42, 0.84, 0.82}, 0.40, 1.23);
  s.lighting.exposure = 0.88;
  s.lighting.uneven_ratio = 1.25;
  s.lighting.uneven_direction = 0.29;
  s.materials.pink = {244, 95, 177};
  s.materials.green = {74, 185, 107};
  s.materials.yellow = {242, 227, 66};
  s.materials.blue = {82, 156, 228};
  s.materials.ball = {251, 108, 20};
  s.lighting.sun_patches = {{{s.ball.position.x, s.ball.position.y}, 600, 500, 0.3, 1.67, 0.25}};
}

// A green cast with teal and light rose markers, dark and noisy.
void greenCastTealRose(SceneSpec& s, int) {
  cast(s, {0.8, 1.3, 0.8}, 0.7);
  s.materials.green = {20, 175, 150};
  s.materials.pink = {250, 175, 205};
  s.lighting.exposure = 0.6;
  s.noise_sigma = 3.0;
}

// Sky blue and yellow-green markers under cold LED, two sun patches.
void coldSkyBlueSun(SceneSpec& s, int) {
  cast(s, kColdLed, 0.7);
  s.materials.blue = {90, 175, 245};
  s.materials.green = {150, 215, 40};
  s.lighting.sun_patches = {{{-1000, -1500}, 700, 400, 0.3, 1.7, 0.2}, {{-3200, 1200}, 500, 300, -0.5, 1.5, 0.15}};
}

void tungstenOverexposedUneven(SceneSpec& s, int) {
  cast(s, kTungsten, 0.8);
  s.lighting.exposure = 1.5;
  s.lighting.uneven_ratio = 3.0;
}

// Light rose dots under a magenta cast, two sun patches.
void magentaCastLightRoseSun(SceneSpec& s, int) {
  cast(s, {1.2, 0.8, 1.2});
  s.materials.pink = {250, 175, 205};
  s.lighting.sun_patches = {{{-2000, 800}, 800, 500, 0.7, 1.8, 0.25}, {{-3600, -1800}, 600, 400, 0.1, 1.6, 0.2}};
}

// Tungsten, saturation 0.4, gamma 1.6, light rose and lemon markers.
void tungstenDesaturatedGammaRoseLemon(SceneSpec& s, int) {
  cast(s, kTungsten, 0.4, 1.6);
  s.materials.pink = {250, 175, 205};
  s.materials.yellow = {245, 245, 80};
}

// A blue-green carpet under cold LED with teal and sky blue dots: the teal
// dots share the carpet's hue, and the carpet's texture reads as sky blue.
void blueGreenCarpetTealSkyBlueCold(SceneSpec& s, int) {
  cast(s, kColdLed);
  s.materials.carpet = {30, 110, 95};
  s.materials.green = {40, 190, 170};
  s.materials.blue = {90, 175, 245};
}

// A 35 degree tilt, tungsten over-exposed.
void tilt35TungstenOverexposed(SceneSpec& s, int) {
  s.cameras = {tiltedCamera(4000, 0.61, 3.5, 1750, 0.03)};
  cast(s, kTungsten, 0.8);
  s.lighting.exposure = 1.4;
}

void greenCastLemonLightOrangeBall(SceneSpec& s, int) {
  cast(s, {0.8, 1.3, 0.8}, 0.8);
  s.materials.yellow = {245, 245, 80};
  s.materials.ball = {255, 165, 60};
  s.lighting.uneven_ratio = 3.0;
}

// A brighter sun patch (2.3) over a lighter ball under tungsten, with
// amber centers: the ball clips in two channels to (255, 254, 143).
void tungstenBrightSunAmberLightBall(SceneSpec& s, int) {
  cast(s, kTungsten, 0.8);
  s.materials.yellow = {250, 165, 0};
  s.materials.ball = {255, 150, 40};
  s.lighting.sun_patches = {{{-1500, 700}, 700, 600, 0.0, 2.3, 0.2}};
}

const std::vector<Condition>& conditions() {
  static const std::vector<Condition> list = {
      // --- casts: the white balance on its warm-cold and green-magenta axes
      {"wb_tungsten", [](SceneSpec& s, int) { cast(s, kTungsten); }},
      {"wb_cold_led", [](SceneSpec& s, int) { cast(s, kColdLed); }},
      {"wb_magenta", [](SceneSpec& s, int) { cast(s, {1.2, 0.8, 1.2}); }},
      {"wb_green", [](SceneSpec& s, int) { cast(s, {0.8, 1.3, 0.8}); }},
      // A mis-set camera under cold LED light (an outsider's scene that lost
      // the whole yellow team and the ball).
      {"wb_cold_desaturated", [](SceneSpec& s, int) { cast(s, {0.72, 1.0, 1.62}, 0.55); }},
      // --- the camera's color processing
      {"saturation_0.4", [](SceneSpec& s, int) { cast(s, {1, 1, 1}, 0.4); }},
      {"saturation_1.3", [](SceneSpec& s, int) { cast(s, {1, 1, 1}, 1.3); }},
      {"gamma_0.6", [](SceneSpec& s, int) { cast(s, {1, 1, 1}, 1, 0.6); }},
      {"gamma_1.6", [](SceneSpec& s, int) { cast(s, {1, 1, 1}, 1, 1.6); }},
      {"tungsten_saturation_0.4", [](SceneSpec& s, int) { cast(s, kTungsten, 0.4); }},
      {"cold_saturation_0.4_gamma_0.6", [](SceneSpec& s, int) { cast(s, kColdLed, 0.4, 0.6); }},
      {"cold_gamma_1.6", [](SceneSpec& s, int) { cast(s, kColdLed, 1, 1.6); }},
      // --- over-exposure: channels clip, so clipped colors lose their hue
      {"overexposed_2x", [](SceneSpec& s, int) { s.lighting.exposure = 2.0; }},
      {"cold_overexposed", [](SceneSpec& s, int) {
         cast(s, kColdLed);
         s.lighting.exposure = 1.5;
       }},
      // --- marker shades (each with the other three at their defaults)
      {"pink_light_rose", [](SceneSpec& s, int) { s.materials.pink = {250, 175, 205}; }},
      {"pink_magenta", [](SceneSpec& s, int) { s.materials.pink = {225, 30, 200}; }},
      {"green_yellow_green", [](SceneSpec& s, int) { s.materials.green = {150, 215, 40}; }},
      {"green_teal", [](SceneSpec& s, int) { s.materials.green = {20, 175, 150}; }},
      {"yellow_lemon", [](SceneSpec& s, int) { s.materials.yellow = {245, 245, 80}; }},
      {"yellow_amber", [](SceneSpec& s, int) { s.materials.yellow = {250, 165, 0}; }},
      {"blue_sky", [](SceneSpec& s, int) { s.materials.blue = {90, 175, 245}; }},
      {"blue_navy", [](SceneSpec& s, int) { s.materials.blue = {20, 30, 125}; }},
      // --- what is neither robot nor ball: hands placing robots (light,
      // medium and dark skin, the forearm too), a shoe by the wall in the
      // ball's own orange and a brown one behind the goal line
      {"hands_and_shoes", [](SceneSpec& s, int) {
         auto box = [&](FieldPoint lo, FieldPoint hi, Rgb c) { s.clutter.push_back({lo, hi, c}); };
         box({-3340, 1710, 150}, {-3260, 1890, 190}, {225, 180, 150});  // hand
         box({-3335, 1890, 185}, {-3265, 2190, 240}, {230, 185, 155});  // forearm
         box({-2740, -690, 160}, {-2660, -510, 200}, {190, 130, 95});
         box({-1240, -1590, 150}, {-1160, -1410, 190}, {110, 70, 50});
         box({-1235, -1410, 185}, {-1165, -1110, 240}, {105, 68, 48});
         box({-2030, 1170, 150}, {-1970, 1230, 210}, {225, 175, 140});  // a fist, nearly ball-sized
         box({-3800, 3040, 0}, {-3520, 3140, 90}, {235, 110, 35});  // orange shoe
         box({-4760, 1500, 0}, {-4660, 1780, 90}, {120, 75, 45});   // brown shoe
       }},
      // --- several at once, as a venue brings them: a cast with the
      // camera's color processing, and dim, noisy, blurred or unevenly lit
      // frames, or pale markers
      {"cold_desaturated_dark_noisy", [](SceneSpec& s, int) {
         cast(s, kColdLed, 0.5);
         s.lighting.exposure = 0.5;
         s.noise_sigma = 3.0;
         s.shot_noise = 0.12;
       }},
      {"magenta_cast_overexposed", [](SceneSpec& s, int) {
         cast(s, {1.2, 0.8, 1.2});
         s.lighting.exposure = 1.5;
       }},
      {"cold_saturation_0.3", [](SceneSpec& s, int) { cast(s, kColdLed, 0.3); }},
      {"tungsten_desaturated_navy_and_amber", [](SceneSpec& s, int) {
         cast(s, kTungsten, 0.6);
         s.materials.blue = {20, 30, 125};
         s.materials.yellow = {250, 165, 0};
       }},
      // Robots in the bright corner at 1224 x 1024 show no side peak at
      // all (pale pink dots beside the black top): read from the ring around
      // the center (completeFromCenter), recall 0.977 -> 0.989; the one
      // still lost stands at the image's edge.
      {"green_cast_desaturated_uneven_light", [](SceneSpec& s, int) {
         cast(s, {0.8, 1.3, 0.8}, 0.6);
         s.lighting.uneven_ratio = 4.0;
         s.lighting.uneven_direction = 0.7;
       }},
      // No pink dot peaks (pale pink under a magenta cast is (255, 224,
      // 255) beside white lines at (255, 255, 255)): this frame's pink is
      // read at the robots' unfilled slots (pinkFromUnseenSlots), and id 9,
      // all four dots pink, is found from its center alone
      // (completeFromCenter). Recall 0.398 / 0.307 -> 0.932 -> 1.000 at
      // both sizes, ids 1.000.
      {"magenta_cast_overexposed_pale_markers", [](SceneSpec& s, int) {
         cast(s, {1.2, 0.8, 1.2});
         s.lighting.exposure = 1.6;
         s.materials.pink = {250, 175, 205};
         s.materials.yellow = {245, 245, 80};
       }},
      // The lines' white and the lit yellow centers clip red under tungsten
      // while their vignetted parts do not, so the same paint reads redder
      // where it is dark: line crossings at the edge were taken for balls
      // (their raw colors look saturated; under the lines' white they are
      // not) and the yellow centers spread toward the ball, whose color only
      // "explained by no class" takes (the ball is redder than every yellow
      // center). Ball recall 0.500 -> 1.000, precision 0.333 -> 1.000.
      {"tungsten_desaturated_vignetting_blur", [](SceneSpec& s, int) {
         cast(s, kTungsten, 0.5, 1.3);
         s.lighting.vignetting = 0.6;
         s.lens_blur_px = 1.2;
       }},
      {"cold_desaturated_vignetting_blur", [](SceneSpec& s, int) {
         cast(s, kColdLed, 0.5, 1.3);
         s.lighting.vignetting = 0.6;
         s.lens_blur_px = 1.2;
       }},
      // The ball's shade nearest to the team's yellow, under the casts that
      // push them together.
      {"tungsten_amber_yellow_red_orange_ball", [](SceneSpec& s, int) {
         cast(s, kTungsten, 0.6);
         s.materials.yellow = {250, 165, 0};
         s.materials.ball = {235, 65, 20};
       }},
      {"cold_lemon_yellow_light_orange_ball_gamma", [](SceneSpec& s, int) {
         cast(s, kColdLed, 0.7, 1.5);
         s.materials.yellow = {245, 245, 80};
         s.materials.ball = {255, 165, 60};
       }},
      // Pale rose dots that made no peak were judged against the retained
      // pink, in a frame alone the fixed reference, which vetoed them: a
      // second search with the frame's own colors finds the robot
      // (searchAgainWithFrameColors). Recall 0.989 -> 1.000 at 2448 x 2048.
      {"green_cast_teal_rose_dark_noisy", greenCastTealRose},
      {"tungsten_magenta_amber_gamma_0.6", [](SceneSpec& s, int) {
         cast(s, kTungsten, 1.0, 0.6);
         s.materials.pink = {225, 30, 200};
         s.materials.yellow = {250, 165, 0};
       }},
      {"magenta_cast_navy_teal_dark_noisy", [](SceneSpec& s, int) {
         cast(s, {1.2, 0.8, 1.2}, 0.8);
         s.materials.blue = {20, 30, 125};
         s.materials.green = {20, 175, 150};
         s.lighting.exposure = 0.5;
         s.noise_sigma = 3.0;
       }},
      {"gray_green_carpet_cold_desaturated_vignetting", [](SceneSpec& s, int) {
         cast(s, kColdLed, 0.5);
         s.materials.carpet = {78, 108, 66};
         s.materials.carpet_texture = 0.28;
         s.lighting.vignetting = 0.6;
       }},
      // Lemon yellow clips green under a green cast, so a yellow center
      // reads as orange under the lines' white as the light orange ball
      // does, and the reddest yellow center explained the ball (ball
      // recall 0.000 at both sizes). Only centers clipped in no channel
      // set the reddest yellow now (learnFrameColors).
      {"green_cast_lemon_light_orange_ball_uneven", greenCastLemonLightOrangeBall},
      // Sky blue clips blue under cold LED, and green too in a sun patch:
      // those centers read (138..162, 255, 255) beside lines of (163, 218,
      // 255), as little saturated as a line crossing, and the pixel
      // stage's gate drops them (recall 0.966 / 0.977, false balls beside
      // the lost robots). Their side blobs give the pose and the frame the
      // center's color (robotsAroundUnpeakedCenters).
      {"cold_sky_blue_yellow_green_sun", coldSkyBlueSun},
      // In the bright half of tungsten over-exposed, 3:1 uneven light the
      // pink dots clip toward white, (253, 249, 244), clearly nearer to
      // neither the frame's pink nor its green: robots whose pink dots made
      // no peak were lost (recall 0.966 / 0.977). The four dots read from
      // the frame now count as markers where they split into two colors by
      // themselves (allSlotsShowMarkers).
      {"tungsten_overexposed_uneven_light", tungstenOverexposedUneven},
      // Six more combinations (this session's widening). The light rose
      // dots in a magenta-cast sun patch peaked only as fast-ball
      // candidates, beside a yellow center that looks orange: with one
      // side blob and no weak peak in the frame the search stopped before
      // reading the frame (recall 0.955 at 2448 x 2048, two false balls);
      // it now reads it.
      {"magenta_cast_light_rose_sun", magentaCastLightRoseSun},
      {"tungsten_navy_shadows_dark", [](SceneSpec& s, int) {
         cast(s, kTungsten, 0.7);
         s.materials.blue = {20, 30, 125};
         s.lighting.exposure = 0.7;
         s.lighting.shadows = {{{-1500, 500}, 900, 500, 0.4, 0.45, 0.3}, {{-3300, -1000}, 700, 600, -0.3, 0.5, 0.3}};
       }},
      {"green_cast_sky_blue_overexposed", [](SceneSpec& s, int) {
         cast(s, {0.8, 1.3, 0.8});
         s.materials.blue = {90, 175, 245};
         s.lighting.exposure = 1.4;
       }},
      {"cold_amber_red_orange_ball_gamma_1.4", [](SceneSpec& s, int) {
         cast(s, kColdLed, 0.6, 1.4);
         s.materials.yellow = {250, 165, 0};
         s.materials.ball = {235, 65, 20};
       }},
      {"tungsten_vivid_lemon_yellow_green_sun", [](SceneSpec& s, int) {
         cast(s, kTungsten, 1.2);
         s.materials.yellow = {245, 245, 80};
         s.materials.green = {150, 215, 40};
         s.lighting.sun_patches = {{{-2500, -500}, 900, 600, 0.2, 1.5, 0.3}};
       }},
      {"magenta_cast_teal_magenta_desaturated_vignetting", [](SceneSpec& s, int) {
         cast(s, {1.25, 0.75, 1.2}, 0.5);
         s.materials.green = {20, 175, 150};
         s.materials.pink = {225, 30, 200};
         s.lighting.vignetting = 0.6;
       }},
      // --- ball shades
      {"ball_red_orange", [](SceneSpec& s, int) { s.materials.ball = {235, 65, 20}; }},
      {"ball_light_orange", [](SceneSpec& s, int) { s.materials.ball = {255, 165, 60}; }},
      // Seven more (the table was all 1.000 again): a 25 degree tilt under
      // the outsider's mis-set cold white balance, the casts' extremes of
      // saturation and gamma, and marker and ball shades under other casts.
      {"tilt_25_cold_desaturated", [](SceneSpec& s, int) {
         s.cameras = {tiltedCamera(4500, 0.44, -1.05, 1750, 0.03)};
         cast(s, {0.72, 1.0, 1.62}, 0.55);
       }},
      {"cold_saturation_0.4_gamma_1.6", [](SceneSpec& s, int) { cast(s, kColdLed, 0.4, 1.6); }},
      {"tungsten_saturation_1.3_gamma_0.6", [](SceneSpec& s, int) { cast(s, kTungsten, 1.3, 0.6); }},
      // Thin lines at 1224 x 1024 under this light made false balls at
      // line crossings (ball precision 0.571): see
      // SceneColorSweepRoseLemon below.
      {"tungsten_saturation_0.4_gamma_1.6_rose_lemon", tungstenDesaturatedGammaRoseLemon},
      {"tilt_35_tungsten_overexposed", tilt35TungstenOverexposed},
      // --- carpets, walls and robot tops other than the preset's, under
      // casts: a gray carpet with wood walls (an outsider's scene), a light
      // green and a blue-green carpet (teal dots on it share its hue under
      // cold light), gray tops; with vivid, dim, shadowed and tilted views
      {"gray_carpet_wood_walls_tungsten", [](SceneSpec& s, int) {
         cast(s, kTungsten, 0.8);
         s.materials.carpet = {105, 105, 100};
         s.materials.wall = {140, 100, 60};
       }},
      {"light_green_carpet_mis_set_cold", [](SceneSpec& s, int) {
         cast(s, {0.72, 1.0, 1.62}, 0.55);
         s.materials.carpet = {95, 175, 95};
       }},
      {"blue_green_carpet_teal_sky_blue_cold", blueGreenCarpetTealSkyBlueCold},
      {"gray_tops_magenta_cast_bright", [](SceneSpec& s, int) {
         cast(s, {1.2, 0.8, 1.2});
         s.materials.robot_top = {70, 70, 75};
         s.lighting.exposure = 1.25;
       }},
      {"amber_red_orange_wood_walls_tungsten_vivid_sun", [](SceneSpec& s, int) {
         cast(s, kTungsten, 1.2);
         s.materials.wall = {140, 100, 60};
         s.materials.yellow = {250, 170, 20};
         s.materials.ball = {235, 65, 20};
         s.lighting.sun_patches = {{{-1800, -900}, 900, 600, 0.5, 1.7, 0.3}};
       }},
      {"green_cast_navy_strong_shadows", [](SceneSpec& s, int) {
         cast(s, {0.8, 1.3, 0.8});
         s.materials.blue = {20, 40, 140};
         s.lighting.object_shadow = 0.85;
         s.lighting.shadows = {{{-2000, 800}, 1200, 500, 0.3, 0.5, 0.3}};
       }},
      {"dim_noisy_gamma_0.6_lemon_magenta", [](SceneSpec& s, int) {
         cast(s, {1, 1, 1}, 1.0, 0.6);
         s.lighting.exposure = 0.5;
         s.noise_sigma = 4;
         s.materials.yellow = {245, 245, 80};
         s.materials.pink = {225, 30, 200};
       }},
      {"tilt_30_cold_uneven_light_rose", [](SceneSpec& s, int) {
         s.cameras = {tiltedCamera(4000, 0.52, -2.0, 1750, 0.03)};
         cast(s, kColdLed, 0.8);
         s.lighting.uneven_ratio = 2.5;
         s.materials.pink = {250, 175, 205};
       }},
      // --- more of both: very dark, blurred and noisy, the ball's lightest
      // and reddest shades, vivid colors at gamma 1.4, a gray carpet under a
      // magenta cast, a 25° tilt under a green cast
      {"very_dark_noisy_tungsten", [](SceneSpec& s, int) {
         cast(s, kTungsten, 0.9);
         s.lighting.exposure = 0.35;
         s.noise_sigma = 3;
       }},
      {"blur_noise_desaturated_pale_cold", [](SceneSpec& s, int) {
         cast(s, kColdLed, 0.6);
         s.lens_blur_px = 1.2;
         s.noise_sigma = 3;
         patternColors(s, {240, 230, 120}, {110, 150, 230}, {130, 220, 140}, {245, 160, 210});
       }},
      {"light_orange_ball_cold_gamma_1.4", [](SceneSpec& s, int) {
         cast(s, kColdLed, 0.8, 1.4);
         s.materials.ball = {255, 165, 60};
       }},
      {"red_orange_ball_green_cast_dim", [](SceneSpec& s, int) {
         cast(s, {0.8, 1.3, 0.8}, 0.9);
         s.lighting.exposure = 0.6;
         s.materials.ball = {235, 65, 20};
       }},
      {"cold_saturation_1.3_gamma_1.4_magenta_teal", [](SceneSpec& s, int) {
         cast(s, kColdLed, 1.3, 1.4);
         s.materials.pink = {225, 30, 200};
         s.materials.green = {40, 190, 170};
       }},
      {"magenta_cast_gray_carpet_amber_sky_blue", [](SceneSpec& s, int) {
         cast(s, {1.2, 0.8, 1.2}, 0.8);
         s.materials.carpet = {105, 105, 100};
         s.materials.yellow = {250, 170, 20};
         s.materials.blue = {90, 175, 245};
       }},
      {"tilt_25_green_cast_uneven_yellow_green", [](SceneSpec& s, int) {
         s.cameras = {tiltedCamera(4000, 0.44, 1.0, 1750, 0.03)};
         cast(s, {0.8, 1.3, 0.8}, 0.8);
         s.lighting.uneven_ratio = 2.5;
         s.materials.green = {150, 215, 40};
       }},
      {"green_cast_navy_amber_dark_noisy", [](SceneSpec& s, int) {
         cast(s, {0.8, 1.3, 0.8}, 0.8);
         s.materials.blue = {20, 30, 125};
         s.materials.yellow = {250, 165, 0};
         s.lighting.exposure = 0.5;
         s.noise_sigma = 3.0;
       }},
      {"cold_magenta_sky_blue_uneven_vignetting", [](SceneSpec& s, int) {
         cast(s, kColdLed, 0.8);
         s.materials.pink = {225, 30, 200};
         s.materials.blue = {90, 175, 245};
         s.lighting.uneven_ratio = 2.5;
         s.lighting.vignetting = 0.5;
       }},
      {"magenta_cast_yellow_green_red_orange_ball_sun", [](SceneSpec& s, int) {
         cast(s, {1.2, 0.8, 1.2}, 0.8);
         s.materials.green = {150, 215, 40};
         s.materials.ball = {235, 65, 20};
         s.lighting.sun_patches = {{{-2200, -600}, 900, 500, 0.4, 1.7, 0.25}};
       }},
      // --- a ball in a marker's color: in a sun patch (1.8) under tungsten
      // the ball clips in red, (255, 209, 30), the color of the yellow
      // centers that clip outside it, (255, 210, 24); it stands alone on
      // the carpet (marker_colored_ball.h; recall 0.000 at both sizes
      // before).
      {"tungsten_sun_over_the_ball", tungstenSunOverTheBall},
      // The ball clipped in two channels, (243, 247, 193), is judged by its
      // disc's unclipped samples (its shaded rim) where nothing around it
      // is a pattern's dot; lemon centers clipped white, (255, 255, 255),
      // by theirs (their rim against the robot's top).
      {"cold_sun_over_the_pale_ball_lemon", coldSunOverThePaleBallLemon},
      // --- drawn at random within the ranges (a check beyond the
      // sweep's own rows).
      // Tungsten at gamma 1.28 with lemon centers and yellow-green dots: at
      // 1224 x 1024 the thin lines' false colors where the center circle
      // crosses the halfway line read as a lemon center, and the crossing's
      // arms as its four dots (dropCentersAloneAtCrossings).
      {"tungsten_gamma_1.3_lemon_yellow_green_light_rose", [](SceneSpec& s, int) {
         cast(s, {1.53, 1.17, 0.68}, 0.73, 1.28);
         s.lighting.uneven_ratio = 2.2;
         s.lighting.uneven_direction = -0.46;
         s.materials.pink = {251, 124, 185};
         s.materials.green = {136, 205, 61};
         s.materials.yellow = {240, 237, 77};
         s.materials.blue = {38, 74, 159};
       }},
      // A warm cast at gamma 1.8, beyond the range (moderate venue
      // #570 at 1.59): teal dots read a third as bright as the amber
      // centers or less ((30, 50, 35) by (189, 107, 59) at 1.59) and were
      // taken for the robot's top (recall 0.761 and 0.807 over the four
      // placements before darkerThanMarker).
      {"warm_gamma_1.8_amber_teal", [](SceneSpec& s, int) {
         cast(s, {1.53, 0.81, 0.68}, 0.44, 1.8);
         s.materials.green = {45, 175, 129};
         s.materials.yellow = {244, 210, 48};
         s.materials.blue = {85, 161, 232};
       }},
      // A ball in a sun patch under a warm cast at saturation 0.4, (239,
      // 169, 121), nearer the yellow class than any other, is judged as a
      // marker-colored ball, which must stand on the carpet; the frame had
      // no carpet peak, and the sun-lit ring lay nearer the teams' classes
      // than the field's (ball 0.000 at 1224 x 1024). The ring is judged by
      // the carpet beside the lines (SceneColorSweepSunBall) and by the
      // carpet beyond a robot's reach around the ball (carpetAroundBall):
      // 1.000 at both sizes, robots too.
      {"warm_saturation_0.4_gamma_1.2_sun_over_the_ball", warmDesaturatedSunOverTheBall},
      // Drawn at random within the ranges: tungsten, saturation
      // 0.4, amber centers, a yellow-green. The frame showed no sample of
      // the field class, its reference 57 from the carpet, and the
      // washed-out ball lay 1.27 of the yellow class's reaches from it: too
      // near to be a shade no class explains, too far to be yellow's (ball
      // 0.250 at 1224 x 1024). Taking the ring's color for the carpet held
      // it, but under gamma 0.6 a robot's top is no darker than a third of
      // its center, and in H.264 nine false balls came of it. The carpet
      // beyond a robot's reach (carpetAroundBall) holds it: 1.000 at both
      // sizes.
      {"tungsten_saturation_0.4_amber_yellow_green_uneven", [](SceneSpec& s, int) {
         cast(s, {1.54, 0.93, 0.67}, 0.4, 0.88);
         s.lighting.exposure = 1.06;
         s.lighting.uneven_ratio = 1.83;
         s.lighting.uneven_direction = -0.19;
         s.materials.pink = {236, 65, 167};
         s.materials.green = {96, 192, 91};
         s.materials.yellow = {249, 175, 11};
         s.materials.blue = {47, 91, 173};
         s.materials.ball = {253, 113, 20};
       }},
      // The ball clipped pale: after the lines' white balance as little
      // saturated as a line crossing, so the pixel stage's color gate
      // dropped it (ball 0.000 at 2448 x 2048, 0.500 at 1224 x 1024, where
      // the fast-ball pass found it twice). The gate now keeps such peaks
      // apart (BlobList::pale) and the detector judges them by shape and
      // place (detector_pale_balls.cpp): 1.000 at both sizes.
      {"tungsten_bright_sun_amber_light_ball", tungstenBrightSunAmberLightBall},
  };
  return list;
}

class SceneColorSweep : public ::testing::TestWithParam<size_t> {};

// Lemon centers at exposure 1.4 under tungsten and saturation 0.4 wash out
// to (250, 253, 200), navy ones stay (75, 85, 95): far apart, but in a
// first frame the split was weighed against the reference green and pink
// (eq. 5.24), which every washed-out marker lies far from, and failed; the
// lemon centers, nearer the lines' white than the one cluster's mean, were
// dropped as line-colored (drawn at random: scripts/random_venues.py 57
// --extreme lost 7 of 8 yellow robots). Now the split is weighed against
// the side colors the frame shows (clusterCenters; without it placement 0
// at 2448 x 2048: recall 0.500), and a center that made no peak inside four
// side blobs needs only be nearer one team than the other
// (teamOfFullPattern), by brightness where it clipped white (without the
// rule placement 1 at 1224 x 1024: recall 0.818; by chromaticity alone,
// ids 0.900). The rest (an open condition below) are robots with two dots
// peaked, or three around a white center, which a sun-clipped ball among
// lit carpet peaks shows too.
TEST(SceneColorSweepWashedLemon, WashedOutCentersKeepTheirTeam) {
  struct Case {
    int placement;
    bool half;
    double recall;  // measured: 0.909, 0.818
  };
  for (const Case& c : {Case{1, true, 0.9}, Case{0, false, 0.8}}) {
    SceneScore s;
    score(conditionScene({"tungsten_exposure_1.4_saturation_0.4_lemon_navy", tungstenExposedWashedLemonNavy},
                         c.placement, c.half),
          1, true, s);
    SCOPED_TRACE("placement " + std::to_string(c.placement) + (c.half ? " at 1224 x 1024" : " at 2448 x 2048"));
    EXPECT_GE(s.recall(), c.recall);
    EXPECT_EQ(s.precision(), 1.0);
    EXPECT_EQ(s.idAccuracy(), 1.0);
    EXPECT_EQ(s.ballRecall(), 1.0);
  }
}

// A streak peak in the shade at a navy robot's edge, (67, 89, 55): the
// carpet's own chromaticity at exposure 1.4 under tungsten, but 49 from the
// field class, which in a frame alone was still its reference, and nearer
// to the ball's mix with that: a false ball in placement 2 at 2448 x 2048
// without the ball. A peak within a color's noise of the carpet beside the
// lines is the carpet's (findBalls).
TEST(SceneColorSweepWashedLemon, AShadedCarpetStreakIsNoBall) {
  SceneScore s;
  score(conditionScene({"tungsten_exposure_1.4_saturation_0.4_lemon_navy", tungstenExposedWashedLemonNavy}, 2, false,
                       false),
        1, true, s);
  EXPECT_EQ(s.balls_detected, 0);
  EXPECT_EQ(s.recall(), 1.0);
}

// The placement of green_cast_teal_rose_dark_noisy at 2448 x 2048 where a
// robot showed its center, a teal and a pale rose blob, its other two rose
// dots no peak: the first search judged them against the reference pink
// (neither green nor pink), the second against the frame's learned pink.
// Recall 0.955 without the second search.
TEST(SceneColorSweepPaleRose, UnpeakedMarkersJudgedByTheFramesOwnColors) {
  expectHeldAt({"green_cast_teal_rose_dark_noisy", greenCastTealRose}, {1}, false);
}

// Centers the pixel stage's gate dropped (cold_sky_blue_yellow_green_sun):
// robots found around them from their side blobs, every id right. Without
// robotsAroundUnpeakedCenters placements 1, 2 and 3 each lost a robot
// (recall 0.955 each) and placement 2 also reported a false ball.
TEST(SceneColorSweepSkyBlue, ClippedCentersReadWhereTheirSideBlobsPutThem) {
  expectHeldAt({"cold_sky_blue_yellow_green_sun", coldSkyBlueSun}, {1, 2, 3}, true);
}

// Light rose dots in a magenta-cast sun patch peak only as fast-ball
// candidates beside a yellow center that looks orange: the center has one
// side blob, and where the frame holds no weak peak at all the search
// stopped before reading the frame (completeFromOneSide): four robots of
// 22 lost (recall 0.818) and two false balls (ball precision 0.333).
TEST(SceneColorSweepLightRose, OneSideBlobWithoutWeakPeaksStillReadsTheFrame) {
  expectHeldAt({"magenta_cast_light_rose_sun", magentaCastLightRoseSun}, {0}, false);
}

// A line crossing at 1224 x 1024 under tungsten, saturation 0.4 and gamma
// 1.6: the Bayer mosaic's false colors along the 1 to 2 px lines, (135,
// 120, 70), lie near no class the frame learned and counted as a ball of
// an unexpected shade. Such a color counts now only where it does not run
// on beyond one ball's rim (ballColorBeyondRim). Without it placement 1 showed two false balls (ball
// precision 0.333), placement 3 one (0.500).
TEST(SceneColorSweepRoseLemon, LineCrossingsFalseColorsAreNoBall) {
  expectHeldAt({"tungsten_saturation_0.4_gamma_1.6_rose_lemon", tungstenDesaturatedGammaRoseLemon}, {1, 3}, true);
}

// A 35 degree tilt under over-exposed tungsten at 1224 x 1024. A far robot
// by the wall shows dots of about 2 px: one green dot peaked, its dim blue
// center (86, 104, 131) only as a weak peak, which made no center; the
// second search now takes a weak peak as the center beside a free side
// blob (searchAgainWithFrameColors). And a T of two lines showed the
// mosaic's pale yellow, (204, 204, 110), a ball of no class's color; now
// its hue lies too near yellow's (hueClearlyBetweenPinkAndYellow). Without
// the first, placement 2 lost the robot (recall 0.955); without the
// second, placement 1 showed a false ball (ball precision 0.500).
TEST(SceneColorSweepFarTilt, WeakCenterBesideASideBlobAndNoPaleYellowBall) {
  expectHeldAt({"tilt_35_tungsten_overexposed", tilt35TungstenOverexposed}, {1, 2}, true);
}

// Random venue #314's ball in a sun patch under a warm cast at saturation
// 0.4, (239, 169, 121), lies nearer the yellow centers than any class, so
// it is judged as a marker-colored ball, which must stand on the carpet.
// The frame had no carpet peak to learn the field class from: it was still
// its reference, 52 from the carpet, the sun-lit ring around the ball lay
// nearer the teams' classes, and no ring sample counted as carpet. The
// ring is now judged with the carpet the pixel stage reads beside the
// lines: without that these placements lose the ball. (Placement 0 lost
// it until the carpet beyond a robot's reach around the ball counted as
// well: carpetAroundBall.)
TEST(SceneColorSweepSunBall, TheRingAroundALitBallIsJudgedByTheCarpetBesideTheLines) {
  for (int k : {1, 2, 3}) {
    SceneScore s;
    score(conditionScene({"warm_saturation_0.4_gamma_1.2_sun_over_the_ball", warmDesaturatedSunOverTheBall}, k, true),
          1, true, s);
    SCOPED_TRACE("placement " + std::to_string(k));
    EXPECT_EQ(s.ballRecall(), 1.0);
    EXPECT_EQ(s.ballPrecision(), 1.0);
  }
}

// That carpet let a thin line's false color through: in the far tilt's
// frame without the ball, the mosaic's pale yellow on the defense area's
// line, (204, 204, 110), nearest yellow, with carpet by the lines on both
// sides, was a marker-colored ball. On a marking such a blob must now show
// a whole ball's round silhouette (a false color follows the line); a
// clipped one is judged by its rim as before (a ball in a sun patch on a
// line, random venues #96 and #212, keeps its ball). Without it placement
// 1 shows a false ball.
TEST(SceneColorSweepFarTilt, AMarkerColoredBlobOnALineMustBeRound) {
  SceneScore s;
  score(conditionScene({"tilt_35_tungsten_overexposed", tilt35TungstenOverexposed}, 1, true, false), 1, true, s);
  EXPECT_EQ(s.balls_detected, 0);
}

// A blue-green carpet under cold LED at 2448 x 2048: a weak peak of the
// carpet's texture (score 0.07, reading as sky blue), a darker patch that
// peaked as a blob (20, 101, 149) near the teal class and a second weak
// peak made a blue robot where none stands, once weak peaks could be
// centers (searchAgainWithFrameColors). Such a pattern may hold no other
// weak peak: without that, placement 3 showed it (precision 0.957).
TEST(SceneColorSweepBlueGreenCarpet, AWeakCenterTakesNoWeakSide) {
  expectHeldAt({"blue_green_carpet_teal_sky_blue_cold", blueGreenCarpetTealSkyBlueCold}, {3}, false);
}

// The same bars as scene_sweep_test.cpp (sweepCondition).
TEST_P(SceneColorSweep, BothTeamsEveryIdAndTheBallUnderAnyColors) { sweepCondition(conditions()[GetParam()]); }

INSTANTIATE_TEST_SUITE_P(Conditions, SceneColorSweep, ::testing::Range<size_t>(0, conditions().size()),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return conditionTestName(conditions()[info.param].name);
                         });

// Tungsten over-exposed under 3:1 uneven light:
// in the bright half the pink dots clip toward white, (255, 230, 254),
// clearly nearer to neither the frame's pink (learned from the dim half) nor
// its green, and only the green dots peak. A robot whose four dots are all
// in view reads them under the light they share and splits them by
// themselves, the redder pink, where the dots seen as blobs keep their
// colors (probeMissingSides). At 1224 x 1024 the first placement went from
// recall 0.909 to 1.000, the third from 0.955 (ids 0.905) to 1.000. Where
// no pink dot of a robot peaked, the hypothesis search counts the dots
// read from the frame as markers when the four split into two colors by
// themselves (allSlotsShowMarkers): the fourth placement 0.909 -> 1.000.
TEST(SceneColorSweepPalePink, ClippedPalePinkSplitFromTheRobotsOwnGreen) {
  expectHeldAt({"tungsten_overexposed_uneven_light", tungstenOverexposedUneven}, {0, 2, 3}, true);
}

// The ball in a sun patch under tungsten, clipped in red to the yellow
// centers' color (marker_colored_ball.h), is found (the sweep's row) and
// centered like any ball: its unclipped, shaded side is the ball's too
// (ball_silhouette.cpp; 3.1 mm off toward the light without).
TEST(SceneColorSweepSunBall, ABallInTheYellowsColorIsCenteredLikeAnyBall) {
  SceneScore s;
  score(conditionScene({"tungsten_sun_over_the_ball", tungstenSunOverTheBall}, 0, false), 1, true, s);
  ASSERT_EQ(s.ball_err.size(), 1u);
  EXPECT_LE(s.ball_err[0], 1.5);
}

// A sun patch (2.0) under a magenta cast with light rose dots: the rose
// dots clip to white. The ball holds.
void magentaCastSunOverTheBallRose(SceneSpec& s, int) {
  cast(s, {1.2, 0.8, 1.2}, 0.8);
  s.materials.pink = {255, 140, 190};
  s.lighting.sun_patches = {{{-1500, 700}, 700, 500, 0.3, 2.0, 0.25}};
}

// Its blue 12 at 2448 x 2048 (placement 1): three green dots read (165, 255, 203) alike,
// the fourth slot, a rose dot, clipped to (254, 250, 253) and peaked only
// as a pale peak. A green there would need half as much light again as
// the three get (slotClippedBeyondItsNeighbours): the slot is the rose.
// Guessed green, the robot was reported as blue 8 (no teammate holds 8).
// (Blue 13 of placement 2 is still read as 8: openConditions.)
TEST(SceneColorSweepSunRose, ALoneSlotClippedBeyondItsNeighboursLightIsTheOtherColor) {
  expectHeldAt({"magenta_cast_sun_over_the_ball_rose", magentaCastSunOverTheBallRose}, {1}, false);
}

// Combinations the defaults do not yet hold (open work; run them with
// --gtest_also_run_disabled_tests, DV_SCENE_FULL=1 and DV_MISSES=1).
const std::vector<Condition>& openConditions() {
  static const std::vector<Condition> list = {
      // See SceneColorSweepSunRose (ids 0.989 at 2448 x 2048: blue 13 is
      // read as 8, one green dot seen and three rose dots clipped to (255,
      // 252, 255); one seen dot gives no plane of the light).
      {"magenta_cast_sun_over_the_ball_rose", magentaCastSunOverTheBallRose},
      // Cold LED over-exposed under 3:1 uneven light: in the brightest
      // corner the lines clip in all three channels, (255, 255, 255), so
      // the frame's white balance is unknown there, and a robot by the wall
      // shows a pale yellow center (254, 255, 214) and whitish pink dots
      // (239, 222, 255), each less saturated than a line crossing may be:
      // the pixel stage's gate drops all of them (recall 0.989 at both
      // sizes).
      {"cold_overexposed_uneven_light", [](SceneSpec& s, int) {
         cast(s, kColdLed, 0.8);
         s.lighting.exposure = 1.5;
         s.lighting.uneven_ratio = 3.0;
         s.lighting.uneven_direction = 1.0;
       }},
      // See SceneColorSweepWashedLemon (recall 0.966 at both sizes: robots
      // of a white-clipped center and one or two peaked side dots, or
      // none).
      {"tungsten_exposure_1.4_saturation_0.4_lemon_navy", tungstenExposedWashedLemonNavy},
  };
  return list;
}

// A sun patch's soft edge under tungsten (placement 2 at 2448 x 2048): a
// blue 6's lone unpeaked side slot, a green dot lit more than its
// neighbours, read clipped toward white and was labelled pink, id 11; the
// robot was then dropped beside the real 11 (recall 0.955 here, 0.989 over
// the four placements). A clipped read beside three seen sides now only
// guesses the slot, and the teammates' ids settle it.
TEST(SceneColorSweepSunEdge, ALoneClippedDotIsSettledByTheTeammatesIds) {
  SceneScore s;
  score(conditionScene({"tungsten_bright_sun_amber_light_ball", tungstenBrightSunAmberLightBall}, 2, false), 1, true,
        s);
  EXPECT_EQ(s.recall(), 1.0);
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// The same condition's ball, clipped pale in every placement at 2448 x
// 2048: its peak is dropped by the color gate and kept apart; one whole
// ball's disc standing on the carpet makes it the ball, centered on that
// disc. Without the pale list and its judge, no ball in any placement.
TEST(SceneColorSweepSunBall, ABallClippedPaleIsFoundByItsShapeAndPlace) {
  for (int k : {0, 1}) {
    SceneScore s;
    score(conditionScene({"tungsten_bright_sun_amber_light_ball", tungstenBrightSunAmberLightBall}, k, false), 1, true,
          s);
    SCOPED_TRACE("placement " + std::to_string(k));
    ASSERT_EQ(s.ball_err.size(), 1u);
    EXPECT_LE(s.ball_err[0], 1.5);
    EXPECT_EQ(s.ballPrecision(), 1.0);
  }
}

class SceneColorSweepOpen : public ::testing::TestWithParam<size_t> {};

TEST_P(SceneColorSweepOpen, DISABLED_BothTeamsEveryIdAndTheBallUnderAnyColors) {
  sweepCondition(openConditions()[GetParam()]);
}

INSTANTIATE_TEST_SUITE_P(Conditions, SceneColorSweepOpen, ::testing::Range<size_t>(0, openConditions().size()),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return conditionTestName(openConditions()[info.param].name);
                         });

}  // namespace
}  // namespace dv

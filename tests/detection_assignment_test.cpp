// Blob assignment on hand-built blob lists: robots from the exact pattern
// geometry under different color looks, clutter, close robots, balls.
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "detection/detector.h"
#include "detection_test_scene.h"
#include "core/error.h"
#include "geometry/field_model.h"

namespace dv {
namespace {

using test::SceneBuilder;
using test::TrueRobot;

// Division B half field seen from the top-down camera.
constexpr double kX0 = 200, kX1 = 4300, kY0 = -2800, kY1 = 2800;

struct Match {
  int found = 0, id_ok = 0, extra = 0;
  double max_pos = 0, max_ang = 0;
};

Match matchRobots(const std::vector<TrueRobot>& truth, const Detections& d) {
  Match m;
  std::vector<bool> used(d.robots.size(), false);
  for (const auto& t : truth) {
    int best = -1;
    double best_d = 60;
    for (size_t i = 0; i < d.robots.size(); ++i) {
      const double e = std::hypot(d.robots[i].position.x - t.position.x,
                                  d.robots[i].position.y - t.position.y);
      if (!used[i] && e < best_d) best_d = e, best = static_cast<int>(i);
    }
    if (best < 0) continue;
    used[best] = true;
    ++m.found;
    const auto& r = d.robots[best];
    if (r.team == t.team && r.id == t.id) ++m.id_ok;
    m.max_pos = std::max(m.max_pos, best_d);
    m.max_ang = std::max(m.max_ang, test::angleError(r.orientation, t.orientation));
  }
  for (bool u : used) m.extra += u ? 0 : 1;
  return m;
}

class FullFieldLooks : public ::testing::TestWithParam<int> {};

TEST_P(FullFieldLooks, FindsEveryRobotWithIdAndTheBallFirst) {
  const test::Look looks[] = {test::lookNormal(), test::lookBlueWhiteBalance(), test::lookDark(),
                              test::lookDesaturated()};
  const CameraModel cam(test::topDownCamera());
  for (unsigned seed = 1; seed <= 5; ++seed) {
    SceneBuilder s(cam, seed * 7 + GetParam(), looks[GetParam()]);
    for (const auto& r : s.randomRobots(11, 11, kX0, kX1, kY0, kY1)) s.addRobot(r);
    const FieldMm ball{1111.0 + 100.0 * seed, -333};
    s.addBall(ball);
    s.addClutter(160, 40, kX0, kX1, kY0, kY1);
    Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
    Detections out;
    det.process(s.list, 1.0, out);
    const Match m = matchRobots(s.robots, out);
    EXPECT_EQ(m.found, 22) << "seed " << seed;
    EXPECT_EQ(m.id_ok, 22) << "seed " << seed;
    EXPECT_EQ(m.extra, 0) << "seed " << seed;
    EXPECT_LT(m.max_pos, 4.0) << "seed " << seed;
    EXPECT_LT(m.max_ang * 180 / kPi, 4.0) << "seed " << seed;
    ASSERT_EQ(out.balls.size(), 1u) << "seed " << seed;
    EXPECT_NEAR(out.balls[0].position.x, ball.x, 5);
    EXPECT_NEAR(out.balls[0].position.y, ball.y, 5);
    EXPECT_DOUBLE_EQ(out.balls[0].position.z, 21.5);
    for (size_t i = 1; i < out.robots.size(); ++i)
      EXPECT_GE(out.robots[i - 1].confidence, out.robots[i].confidence);
  }
}

INSTANTIATE_TEST_SUITE_P(Looks, FullFieldLooks, ::testing::Values(0, 1, 2, 3));

TEST(DetectionAssignment, RobotsTouchingAreSeparated) {
  const CameraModel cam(test::topDownCamera());
  SceneBuilder s(cam, 3);
  // Fronts facing each other, side by side, back to back: 180 mm apart.
  s.addRobot({Team::Yellow, 3, {1500, 0}, 0});
  s.addRobot({Team::Blue, 5, {1680, 0}, kPi});
  s.addRobot({Team::Yellow, 7, {1500, 180}, kPi / 2});
  s.addRobot({Team::Blue, 0, {1680, 180}, 1.0});
  s.addRobot({Team::Yellow, 12, {1500, -180}, -2.5});
  s.addRobot({Team::Blue, 9, {1680, -180}, 2.0});
  s.addRobot({Team::Blue, 8, {1860, -180}, -0.3});
  Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
  Detections out;
  det.process(s.list, 0, out);
  const Match m = matchRobots(s.robots, out);
  EXPECT_EQ(m.found, 7);
  EXPECT_EQ(m.id_ok, 7);
  EXPECT_EQ(m.extra, 0);
}

TEST(DetectionAssignment, OnlyOneTeamUnderBlueWhiteBalanceStaysYellow) {
  const CameraModel cam(test::topDownCamera());
  SceneBuilder s(cam, 4, test::lookBlueWhiteBalance());
  for (auto r : s.randomRobots(6, 0, kX0, kX1, kY0, kY1)) s.addRobot(r);
  Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
  Detections out;
  det.process(s.list, 0, out);
  const Match m = matchRobots(s.robots, out);
  EXPECT_EQ(m.found, 6);
  EXPECT_EQ(m.id_ok, 6);
}

TEST(DetectionAssignment, TiltedCameraAndTeamHeights) {
  // A side view: positions must come out at each team's height.
  const CameraModel cam(test::lookAtCamera({-1500, -2500, 3500}, {2000, 0, 0}, 900));
  DetectorOptions opt;
  opt.robot_height_yellow = 140;
  opt.robot_height_blue = 120;
  SceneBuilder s(cam, 5, test::lookNormal(), 0.5);
  TrueRobot a{Team::Yellow, 4, {1500, -500}, 0.3};
  TrueRobot b{Team::Blue, 11, {2600, 700}, -1.2};
  b.height = 120;
  s.addRobot(a);
  s.addRobot(b);
  s.addBall({2000, 100});
  Detector det(cam, FieldModel::divisionB(), opt);
  Detections out;
  det.process(s.list, 0, out);
  const Match m = matchRobots(s.robots, out);
  ASSERT_EQ(m.found, 2);
  EXPECT_EQ(m.id_ok, 2);
  EXPECT_LT(m.max_pos, 2.0);
  for (const auto& r : out.robots)
    EXPECT_DOUBLE_EQ(r.height, r.team == Team::Yellow ? 140.0 : 120.0);
  ASSERT_GE(out.balls.size(), 1u);
  EXPECT_NEAR(out.balls[0].position.x, 2000, 3);
  EXPECT_NEAR(out.balls[0].position.y, 100, 3);
  // The reported pixel is where the robot center appears in the image.
  const auto px = cam.fieldToImage({a.position.x, a.position.y, 140});
  ASSERT_TRUE(px);
  for (const auto& r : out.robots)
    if (r.team == Team::Yellow) {
      EXPECT_NEAR(r.pixel.u, px->u, 1.0);
      EXPECT_NEAR(r.pixel.v, px->v, 1.0);
    }
}

TEST(DetectionBalls, PinkBlobApartIsNotABall) {
  const CameraModel cam(test::topDownCamera());
  for (int with_ball = 0; with_ball < 2; ++with_ball) {
    SceneBuilder s(cam, 11 + with_ball);
    for (auto r : s.randomRobots(3, 3, kX0, 2000, kY0, kY1)) s.addRobot(r);
    s.addBlob({3500, 1500, 140}, SceneBuilder::kPink, 0.9f);  // a lost side blob
    s.addBlob({3800, -1500, 140}, SceneBuilder::kPink, 0.9f);
    if (with_ball) s.addBall({3000, 0}, 0.6f);
    Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
    Detections out;
    det.process(s.list, 0, out);
    ASSERT_EQ(out.balls.size(), static_cast<size_t>(with_ball));
    if (with_ball) {
      EXPECT_NEAR(out.balls[0].position.x, 3000, 5);
    }
  }
}

// A ball over-exposed in a sun patch: its blob's mean clips in red and
// green, and only the frame's unclipped samples around it, its shaded rim,
// show its color. Alone on the carpet it is the ball. With a pattern's dot
// beside it, it may be a lost robot's clipped center: it is none where the
// ring around it shows that robot's dark top, and the ball where it shows
// the lit carpet (the dot a peak of that carpet: under a green cast one
// stood 70 mm from the ball).
TEST(DetectionBalls, AnOverExposedBlobIsJudgedByItsRimWhereItStandsAlone) {
  const CameraModel cam(test::topDownCamera());
  const FieldMm ball{3000, 1000};
  enum Case { kAlone, kDotOnLitCarpet, kDotOnATop };
  for (int k = kAlone; k <= kDotOnATop; ++k) {
    SCOPED_TRACE(k);
    SceneBuilder s(cam, 31, {{1, 1, 1}, 1, 1, 0});
    for (auto r : s.randomRobots(3, 3, kX0, 2000, kY0, kY1)) s.addRobot(r);
    s.addBlob({ball.x, ball.y, 21.5}, ColorRef{255, 255, 130}, 0.8f);
    if (k != kAlone) s.addBlob({ball.x + 60, ball.y, 140}, SceneBuilder::kGreen, 0.9f);
    cv::Mat image(static_cast<int>(cam.calibration().image_height), static_cast<int>(cam.calibration().image_width),
                  CV_8UC3, cv::Scalar(50, 110, 40));
    const auto px = cam.fieldToImage({ball.x, ball.y, 21.5});
    ASSERT_TRUE(px);
    const cv::Point c(static_cast<int>(std::lround(px->u)), static_cast<int>(std::lround(px->v)));
    if (k == kDotOnLitCarpet) cv::circle(image, c, 40, cv::Scalar(100, 220, 80), cv::FILLED);  // sun patch (BGR)
    if (k == kDotOnATop) cv::circle(image, c, 14, cv::Scalar(20, 20, 20), cv::FILLED);        // 85 mm
    cv::circle(image, c, 3, cv::Scalar(30, 110, 230), cv::FILLED);                            // rim
    cv::circle(image, c, 1, cv::Scalar(130, 255, 255), cv::FILLED);                           // clipped top
    Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
    Detections out;
    det.process(s.list, 0, out, FrameView{&image, BayerPattern::None});
    if (k == kDotOnATop) {
      EXPECT_TRUE(out.balls.empty());
    } else {
      ASSERT_EQ(out.balls.size(), 1u);
      EXPECT_NEAR(out.balls[0].position.x, ball.x, 10);
      EXPECT_NEAR(out.balls[0].position.y, ball.y, 10);
    }
    // Without the frame the clipped color says too little.
    det.process(s.list, 1, out);
    EXPECT_TRUE(out.balls.empty());
  }
}

// A blob of a color no class explains, in a hue not clearly the ball's: a
// kicked ball that a cold cast and H.264 washed out to a pale yellow-gray.
// Alone on the carpet it is the ball. Beside a pattern's dot, on a robot's
// dark top (a lost robot's washed-out center) or on a marking (a thin
// line's false colors) it is none, nor without the frame around it.
TEST(DetectionBalls, AWashedOutBlobAloneOnTheCarpetIsTheBall) {
  const CameraModel cam(test::topDownCamera());
  constexpr ColorRef kWashed{160, 140, 80};
  enum Case { kAlone, kDot, kTop, kMarking };
  for (int k = kAlone; k <= kMarking; ++k) {
    SCOPED_TRACE(k);
    const FieldMm ball = k == kMarking ? FieldMm{3500, 500} : FieldMm{3000, 1000};  // the defense area's line
    SceneBuilder s(cam, 31, {{1, 1, 1}, 1, 1, 0});
    for (auto r : s.randomRobots(3, 3, kX0, 2000, kY0, kY1)) s.addRobot(r);
    s.addBlob({ball.x, ball.y, 21.5}, kWashed, 0.8f);
    if (k == kDot) s.addBlob({ball.x + 60, ball.y, 140}, SceneBuilder::kGreen, 0.9f);
    cv::Mat image(static_cast<int>(cam.calibration().image_height), static_cast<int>(cam.calibration().image_width),
                  CV_8UC3, cv::Scalar(50, 110, 40));
    const auto px = cam.fieldToImage({ball.x, ball.y, 21.5});
    ASSERT_TRUE(px);
    const cv::Point c(static_cast<int>(std::lround(px->u)), static_cast<int>(std::lround(px->v)));
    if (k == kTop) cv::circle(image, c, 14, cv::Scalar(20, 20, 20), cv::FILLED);  // 85 mm
    cv::circle(image, c, 4, cv::Scalar(kWashed.b, kWashed.g, kWashed.r), cv::FILLED);
    Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
    Detections out;
    det.process(s.list, 0, out, FrameView{&image, BayerPattern::None});
    if (k == kAlone) {
      ASSERT_EQ(out.balls.size(), 1u);
      EXPECT_NEAR(out.balls[0].position.x, ball.x, 10);
      EXPECT_NEAR(out.balls[0].position.y, ball.y, 10);
    } else {
      EXPECT_TRUE(out.balls.empty());
    }
    det.process(s.list, 1, out);
    EXPECT_TRUE(out.balls.empty()) << "without the frame";
  }
}

TEST(DetectionBalls, LineCrossingsAndCarpetAreNoBalls) {
  const CameraModel cam(test::topDownCamera());
  for (const auto& look : {test::lookNormal(), test::lookBlueWhiteBalance(), test::lookDark()}) {
    SceneBuilder s(cam, 21, look);
    for (auto r : s.randomRobots(4, 4, kX0, kX1, kY0, kY1)) s.addRobot(r);
    s.addClutter(150, 60, kX0, kX1, kY0, kY1);
    Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
    Detections out;
    det.process(s.list, 0, out);
    EXPECT_TRUE(out.balls.empty()) << out.balls.size() << " ghost balls";
  }
}

TEST(DetectionBalls, BallTooCloseToARobotIsRejectedButDribbledBallIsKept) {
  const CameraModel cam(test::topDownCamera());
  SceneBuilder s(cam, 5);
  s.addRobot({Team::Yellow, 2, {1000, 0}, 0});
  s.addRobot({Team::Blue, 6, {2000, 0}, 0});
  s.addBall({1000 + 40, 40});            // on top of the yellow robot: impossible
  s.addBall({2000 + 55 + 22, 0});        // at the blue robot's flat front
  Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
  Detections out;
  det.process(s.list, 0, out);
  ASSERT_EQ(out.balls.size(), 1u);
  EXPECT_NEAR(out.balls[0].position.x, 2077, 5);
  EXPECT_EQ(out.robots.size(), 2u);
}

TEST(DetectionBalls, RealBallRanksFirstAmongOrangeishBlobs) {
  const CameraModel cam(test::topDownCamera());
  SceneBuilder s(cam, 8);
  for (auto r : s.randomRobots(4, 4, kX0, kX1, kY0, kY1)) s.addRobot(r);
  s.addBall({2500, 900});
  // A reddish-brown spot on the carpet: orange-ish, but weak and dull.
  s.addBlob({1300, -2000, 0}, ColorRef{120, 90, 60}, 0.3f);
  Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
  Detections out;
  det.process(s.list, 0, out);
  ASSERT_GE(out.balls.size(), 1u);
  EXPECT_NEAR(out.balls[0].position.x, 2500, 5);
  EXPECT_NEAR(out.balls[0].position.y, 900, 5);
  for (size_t i = 1; i < out.balls.size(); ++i)
    EXPECT_LT(out.balls[i].confidence, out.balls[0].confidence);
}

// Streak blobs (the pixel stage's fast-ball pass) carry the ball's color
// mixed with the carpet's. They are judged on the mixing lines from the
// field color: orange mixed with carpet is a ball, pink mixed with carpet is
// not, a streak inside a robot is not, and a streak never stands in for a
// robot's blob.
TEST(DetectionBalls, StreaksAreBallsOnlyOnTheOrangeMixingLine) {
  const CameraModel cam(test::topDownCamera());
  auto mix = [](ColorRef a, ColorRef b, float wa) {
    return ColorRef{wa * a.r + (1 - wa) * b.r, wa * a.g + (1 - wa) * b.g, wa * a.b + (1 - wa) * b.b};
  };
  auto addStreak = [](SceneBuilder& s, const FieldPoint& p, ColorRef c) {
    s.addBlob(p, c, 0.8f);
    s.list.blobs.back().streak = true;
  };
  for (const auto& look : {test::lookNormal(), test::lookBlueWhiteBalance(), test::lookDark()}) {
    SceneBuilder s(cam, 31, look);
    for (auto r : s.randomRobots(3, 3, kX0, 1500, kY0, kY1)) s.addRobot(r);
    // A robot whose center blob is missing, with a yellow streak where the
    // center would be: the streak must not complete the robot.
    TrueRobot hidden{Team::Yellow, 9, {3400, -1800}, 0.3};
    hidden.present[0] = false;
    s.addRobot(hidden);
    addStreak(s, {3400, -1800, 140}, SceneBuilder::kYellow);
    // Pink mixed with the carpet, apart from everything.
    addStreak(s, {3000, 1800, 21.5}, mix(SceneBuilder::kPink, SceneBuilder::kCarpet, 0.7f));
    // An orange-ish streak inside a robot's top.
    const TrueRobot& r0 = s.robots[0];
    addStreak(s, {r0.position.x + 30, r0.position.y, 21.5}, mix(SceneBuilder::kOrange, SceneBuilder::kCarpet, 0.7f));
    // The fast ball: 60 % orange, 40 % carpet.
    addStreak(s, {2500, 600, 21.5}, mix(SceneBuilder::kOrange, SceneBuilder::kCarpet, 0.6f));
    Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
    Detections out;
    det.process(s.list, 0, out);
    ASSERT_EQ(out.balls.size(), 1u);
    EXPECT_NEAR(out.balls[0].position.x, 2500, 5);
    EXPECT_NEAR(out.balls[0].position.y, 600, 5);
    EXPECT_EQ(out.robots.size(), 6u);
    for (const auto& r : out.robots) EXPECT_GT(std::hypot(r.position.x - 3400, r.position.y + 1800), 200);
  }
}

// A streak that continues no ball track is not reported beside a round
// ball: in a frame that has a ball, an orange-ish region elsewhere is more
// likely a colored part of the scene than a second ball.
TEST(DetectionBalls, StreakBesideARoundBallNeedsATrack) {
  const CameraModel cam(test::topDownCamera());
  SceneBuilder s(cam, 41);
  for (auto r : s.randomRobots(3, 3, kX0, 1500, kY0, kY1)) s.addRobot(r);
  s.addBall({2500, 600});
  s.addBlob({3500, -1500, 21.5}, ColorRef{200, 118, 28}, 0.8f);
  s.list.blobs.back().streak = true;
  Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
  Detections out;
  det.process(s.list, 0, out);
  ASSERT_EQ(out.balls.size(), 1u);
  EXPECT_NEAR(out.balls[0].position.x, 2500, 5);
  // Alone, the same streak is the ball.
  s.list.blobs.erase(s.list.blobs.end() - 2);
  det.reset();
  det.process(s.list, 0, out);
  ASSERT_EQ(out.balls.size(), 1u);
  EXPECT_NEAR(out.balls[0].position.x, 3500, 5);
}

TEST(DetectionAssignment, EmptyAndDegenerateInputDoNotCrash) {
  const CameraModel cam(test::topDownCamera());
  Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
  Detections out;
  BlobList empty;
  det.process(empty, 0, out);
  EXPECT_TRUE(out.robots.empty());
  EXPECT_TRUE(out.balls.empty());
  BlobList bad;
  Blob b;
  b.position = {std::nan(""), 0};
  bad.blobs.push_back(b);
  b.position = {1e9, -1e9};
  bad.blobs.push_back(b);
  bad.blobs.push_back(b);  // two blobs at the same place
  det.process(bad, 1, out);
  EXPECT_TRUE(out.robots.empty());
  BlobList above;  // plane above the camera: nothing can be projected
  above.plane_height = 1e6;
  above.blobs.push_back(Blob{});
  det.process(above, 2, out);
  EXPECT_TRUE(out.robots.empty());
}

}  // namespace
}  // namespace dv

namespace dv {
namespace {

TEST(DetectionOptions, ImpossibleValuesAreOneClearError) {
  const CameraModel cam(test::topDownCamera());
  auto expectError = [&](DetectorOptions o, const std::string& needle) {
    try {
      Detector d(cam, FieldModel::divisionB(), o);
      ADD_FAILURE() << "no error for " << needle;
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), "detector options");
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  DetectorOptions o;
  o.robot_height_blue = -5;
  expectError(o, "robot_height_blue");
  o = {};
  o.retention_force = 0.95;
  expectError(o, "retention_force");
  o = {};
  o.min_side_blobs = 2;
  expectError(o, "min_side_blobs");
  o = {};
  o.robot_height_yellow = 9000;  // above the camera at 4.5 m
  expectError(o, "below the camera");
  o = {};
  o.ball_radius = std::nan("");
  expectError(o, "ball_radius");
  EXPECT_NO_THROW(Detector(cam, FieldModel::divisionB(), DetectorOptions{}));
}

}  // namespace
}  // namespace dv

namespace dv {
namespace {

TEST(DetectionAssignment, MissingSideBlobTakesTheIdNoOtherRobotHolds) {
  const CameraModel cam(test::topDownCamera());
  // Robot A (id 0: FL P, BL G, BR P, FR P) misses its front-left blob; taken
  // as green that would read as id 1, which robot B shows in full.
  auto colors = patternColors(0);
  ASSERT_EQ(colors[kFrontLeft], MarkerColor::Pink);
  colors[kFrontLeft] = MarkerColor::Green;
  const int guess = patternId(colors);
  test::TrueRobot a{Team::Yellow, 0, {1500, 500}, 0.7};
  a.present = {true, false, true, true, true};
  const test::TrueRobot b{Team::Yellow, guess, {2500, -500}, -0.4};
  const test::TrueRobot c{Team::Blue, 4, {3000, 1000}, 2.0};
  for (bool with_b : {false, true}) {
    for (bool report_guesses : {false, true}) {
      SceneBuilder s(cam, 77);
      s.addRobot(a);
      if (with_b) s.addRobot(b);
      s.addRobot(c);
      DetectorOptions opt;
      opt.report_guessed_ids = report_guesses;
      Detector det(cam, FieldModel::divisionB(), opt);
      Detections out;
      det.process(s.list, 0, out);
      const RobotDetection* found = nullptr;
      for (const auto& r : out.robots)
        if (std::hypot(r.position.x - a.position.x, r.position.y - a.position.y) < 10) found = &r;
      SCOPED_TRACE(std::string(with_b ? "with B" : "alone") + (report_guesses ? ", guesses" : ""));
      // Alone, A's id is one of two: no id rather than a wrong one.
      if (!with_b && !report_guesses) {
        EXPECT_EQ(found, nullptr);
        continue;
      }
      ASSERT_NE(found, nullptr);
      EXPECT_EQ(found->team, Team::Yellow);
      EXPECT_EQ(found->id, with_b ? 0 : guess);
      EXPECT_LT(found->confidence, 0.6f) << "a missing blob halves the confidence";
    }
  }
}

// A robot cut by the image border shows its center and two side blobs; its
// other two slots lie outside the image. It is one of four ids: reported
// only when fully seen teammates hold the other three. The same two blobs
// missing inside the image are no robot.
TEST(DetectionAssignment, RobotCutByTheImageBorderNeedsItsIdFromTeammates) {
  const CameraModel cam(test::topDownCamera());
  const auto& calib = cam.calibration();
  const auto at = cam.imageToField({5, calib.image_height / 2.0}, 140);
  ASSERT_TRUE(at);
  // An orientation that puts exactly two side blobs (discs included) out.
  test::TrueRobot a{Team::Yellow, 6, at->xy(), 0};
  int out_count = 0;
  for (double o = 0; o < 2 * kPi && out_count != 2; o += 0.1) {
    a.orientation = o;
    out_count = 0;
    for (int i = 0; i < 4; ++i) {
      const FieldMm off = RobotPatternGeometry::kSideBlobs[i];
      const double x = a.position.x + std::cos(o) * off.x - std::sin(o) * off.y;
      const double y = a.position.y + std::sin(o) * off.x + std::cos(o) * off.y;
      bool out = false;
      for (int k = 0; k < 8; ++k) {
        const auto px = cam.fieldToImage({x + 20 * std::cos(k * kPi / 4), y + 20 * std::sin(k * kPi / 4), 140});
        out |= !px || px->u < -0.5 || px->u > calib.image_width - 0.5;
      }
      a.present[i + 1] = !out;
      out_count += out;
    }
  }
  ASSERT_EQ(out_count, 2);
  // The ids A could be: its seen sides, the unseen two either color.
  std::vector<int> others;
  for (int pinks = 0; pinks < 4; ++pinks) {
    auto c = patternColors(a.id);
    int k = 0;
    for (int i = 0; i < 4; ++i)
      if (!a.present[i + 1]) c[i] = pinks >> k++ & 1 ? MarkerColor::Pink : MarkerColor::Green;
    if (patternId(c) != a.id) others.push_back(patternId(c));
  }
  ASSERT_EQ(others.size(), 3u);
  auto run = [&](const test::TrueRobot& robot, int teammates) {
    SceneBuilder s(cam, 5);
    s.addRobot(robot);
    for (int i = 0; i < teammates; ++i)
      s.addRobot({Team::Yellow, others[i], {2250.0 + 400 * i, 900}, 0.3 * i});
    s.addRobot({Team::Blue, 3, {2600, -900}, 1.0});
    Detector det(cam, FieldModel::divisionB(), DetectorOptions{});
    Detections out;
    det.process(s.list, 0, out);
    for (const auto& r : out.robots)
      if (std::hypot(r.position.x - robot.position.x, r.position.y - robot.position.y) < 15) return r.id;
    return -1;
  };
  EXPECT_EQ(run(a, 0), -1) << "one of four ids";
  EXPECT_EQ(run(a, 2), -1) << "one of two ids";
  EXPECT_EQ(run(a, 3), a.id);
  // The same blobs missing in the middle of the image: no robot.
  test::TrueRobot inside = a;
  inside.position = {2250, -600};
  EXPECT_EQ(run(inside, 3), -1);
}

}  // namespace
}  // namespace dv

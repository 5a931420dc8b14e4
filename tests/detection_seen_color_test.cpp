// Side slots that did not peak, read from the frame (detection/seen_color.h):
// on rendered frames, the color the camera saw at a robot's slot tells its
// marker, also where the dot is cut by the image border or a few pixels
// tall; the detector takes it for a side blob the blob list lacks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "detection/color_classes.h"
#include "detection/detector.h"
#include "detection/seen_color.h"
#include "detection/weak_sides.h"
#include "scene_scoring.h"

namespace dv {
namespace {

ColorVec feature(const ColorRef& c) { return colorFeature(c.r, c.g, c.b); }

// Every side dot of the side view's robots (1.3..7 m away, the far ones
// 2 pixels tall), read where the truth puts it: clearly nearer to the
// reference pink or green it is, wherever a part of it is in the image.
TEST(DetectionSeenColor, SideViewDotsShowTheirMarker) {
  const SceneSpec spec = presetScene("side_view");
  Renderer renderer(spec);
  const CameraModel cam(spec.cameras[0].calib);
  const RenderedFrame frame = renderer.render(0, 0);
  const FrameView view{&frame.image, test::pipelineBayer(spec)};
  const DetectorOptions opt;
  const ColorVec green = feature(opt.ref_green), pink = feature(opt.ref_pink);
  int read = 0;
  for (const auto* list : {&frame.truth.robots_yellow(), &frame.truth.robots_blue()})
    for (const auto& t : *list) {
      const auto colors = patternColors(static_cast<int>(t.robot_id()));
      for (int s = 1; s <= 4; ++s) {
        const FieldMm p = slotPosition({t.x(), t.y()}, t.orientation(), s);
        const SeenColor seen = seenDiscColor(view, cam, {p.x, p.y, t.height()}, opt.probe_radius);
        if (seen.share < opt.min_probe_share) continue;
        ++read;
        const int label = weakSideColor(colorFeature(seen.rgb[0], seen.rgb[1], seen.rgb[2]), green, pink,
                                        static_cast<float>(opt.weak_color_margin));
        EXPECT_EQ(label, colors[s - 1] == MarkerColor::Pink ? 1 : 0) << "robot " << t.robot_id() << " slot " << s;
      }
    }
  EXPECT_GE(read, 36);
  // Outside the image nothing is seen.
  EXPECT_EQ(seenDiscColor(view, cam, {-1200, -3600, 140}, 13).share, 0);
}

// The top-down half field at 1224 x 1024 with 4 + 4 robots, and a blob list
// edited per robot by `edit(blobs, slot k of robot n on the blob plane, n)`;
// how many robots the detector finds at their truth with the right team and
// id (guessed ids not reported), with the frame and with blobs alone, and how
// many it reports there with a wrong one.
struct RobotsFound {
  int right[2] = {0, 0}, wrong[2] = {0, 0};  // [0]: with the frame, [1]: blobs alone
  double worst_orientation = 0;  // rad, of the robots found right with the frame
};

template <class Edit>
RobotsFound robotsFoundAfter(Edit&& edit, void (*light)(SceneSpec&) = nullptr) {
  SceneSpec spec = presetScene("top_down_div_b_half");
  if (light) light(spec);
  test::halveResolution(spec);
  spec.robots = placeRandomRobots(spec, 0, 4, 4, 7, 200, 30);
  Renderer renderer(spec);
  const CameraModel cam(spec.cameras[0].calib);
  PipelineOptions popt;
  popt.bayer = test::pipelineBayer(spec);
  CpuPipeline pipeline(cam, spec.field, popt);
  const RenderedFrame frame = renderer.render(0, 0);
  BlobList blobs;
  EXPECT_TRUE(pipeline.process(frame.image, blobs));
  const Eigen::Vector3d c = cam.position();
  int n = 0;
  for (const auto* list : {&frame.truth.robots_yellow(), &frame.truth.robots_blue()})
    for (const auto& t : *list) {
      FieldMm slots[5];
      for (int k = 0; k < 5; ++k) {
        const FieldMm q = slotPosition({t.x(), t.y()}, t.orientation(), k);
        const double s = (c.z() - blobs.plane_height) / (c.z() - t.height());
        slots[k] = {c.x() + s * (q.x - c.x()), c.y() + s * (q.y - c.y())};
      }
      edit(blobs, slots, n++);
    }
  DetectorOptions opt;
  opt.tracking = false;
  opt.report_guessed_ids = false;
  RobotsFound found;
  for (bool with_frame : {true, false}) {
    Detector det(cam, spec.field, opt);
    Detections out;
    det.process(blobs, 0, out, with_frame ? FrameView{&frame.image, popt.bayer} : FrameView{});
    for (const auto* list : {&frame.truth.robots_yellow(), &frame.truth.robots_blue()})
      for (const auto& t : *list)
        for (const auto& r : out.robots)
          if (std::hypot(r.position.x - t.x(), r.position.y - t.y()) < 20) {
            const bool ok = r.id == static_cast<int>(t.robot_id()) &&
                            r.team == (list == &frame.truth.robots_yellow() ? Team::Yellow : Team::Blue);
            ++(ok ? found.right : found.wrong)[with_frame ? 0 : 1];
            if (ok && with_frame)
              found.worst_orientation = std::max(
                  found.worst_orientation, std::abs(std::remainder(r.orientation - t.orientation(), 2 * kPi)));
          }
  }
  return found;
}

void removeNear(std::vector<Blob>& list, const FieldMm& p) {
  list.erase(std::remove_if(list.begin(), list.end(),
                            [&](const Blob& b) { return std::hypot(b.position.x - p.x, b.position.y - p.y) < 15; }),
             list.end());
}

// A robot whose side blob is taken out of the blob list (and every weak peak
// near it): with the frame the detector reads the slot and reports the
// right id even when guessed ids are not; without it the id is one of two
// (a teammate seen whole may still rule one out).
TEST(DetectionSeenColor, MissingSideBlobReadFromTheFrame) {
  const RobotsFound f = robotsFoundAfter([](BlobList& blobs, const FieldMm* slot, int n) {
    removeNear(blobs.blobs, slot[1 + n % 4]);
    removeNear(blobs.weak, slot[1 + n % 4]);
  });
  EXPECT_EQ(f.right[0], 8);
  EXPECT_LT(f.right[1], 8);
  EXPECT_EQ(f.wrong[0], 0);
  EXPECT_EQ(f.wrong[1], 0);
}

// Two side blobs of every robot taken out (as where JPEG's half-resolution
// chroma runs a green dot into the carpet): the center and the two side
// blobs left fix the pose, and the frame shows markers at the other two
// slots, so every robot is found with its id; from blobs alone none is (no
// slot is outside the image).
TEST(DetectionSeenColor, TwoMissingSideBlobsReadFromTheFrame) {
  const RobotsFound f = robotsFoundAfter([](BlobList& blobs, const FieldMm* slot, int n) {
    for (int k : {1 + n % 4, 1 + (n + 1 + n / 4) % 4}) {  // adjacent pairs, then diagonal ones
      removeNear(blobs.blobs, slot[k]);
      removeNear(blobs.weak, slot[k]);
    }
  });
  EXPECT_EQ(f.right[0], 8);
  EXPECT_EQ(f.right[1], 0);
}

// Three side blobs of every robot taken out (pale dots beside the black
// top that lost their chroma to a cast, desaturation or clipping, where one
// green dot still peaks): the center and the side blob left fix the pose
// for the one slot the side blob may fill with markers shown at the other
// three, so the robots are found with their ids; from blobs alone none is.
TEST(DetectionSeenColor, ThreeMissingSideBlobsReadFromTheFrame) {
  const RobotsFound f = robotsFoundAfter([](BlobList& blobs, const FieldMm* slot, int n) {
    for (int k = 1; k <= 4; ++k) {
      if (k == 1 + n % 4) continue;
      removeNear(blobs.blobs, slot[k]);
      removeNear(blobs.weak, slot[k]);
    }
  });
  EXPECT_EQ(f.right[0], 8);
  EXPECT_EQ(f.wrong[0], 0);
  EXPECT_EQ(f.right[1], 0);
}

// A magenta cast over-exposed, pale pink dots: they clip to (255, 224, 255)
// beside lines at (255, 255, 255) and none makes a side blob, so no pink is
// learned from the blobs; the pink the frame shows at the robots' unfilled
// slots is (pinkFromUnseenSlots), and every robot with a green side blob
// left to pose it is found with its id. With the reference pink, a pale
// dot's color is clearly nearer to neither, and no id is known.
TEST(DetectionSeenColor, PalePinkNoDotPeaksIsLearnedFromTheSlots) {
  const RobotsFound f = robotsFoundAfter([](BlobList&, const FieldMm*, int) {},
                                         [](SceneSpec& s) {
                                           s.lighting.white_balance = {1.2, 0.8, 1.2};
                                           s.lighting.exposure = 1.6;
                                           s.materials.pink = {250, 175, 205};
                                         });
  EXPECT_GE(f.right[0], 6);
  EXPECT_EQ(f.wrong[0], 0);
}

// All four side blobs of every robot taken out, and every weak peak near
// them (pale dots that make no peak at all): the frame read along the ring
// around each center gives the one orientation that puts all four slots on
// markers, and every robot is found with its id and its orientation within
// a few degrees; from blobs alone none is.
TEST(DetectionSeenColor, NoSidePeakReadFromTheRing) {
  const RobotsFound f = robotsFoundAfter([](BlobList& blobs, const FieldMm* slot, int) {
    for (int k = 1; k < 5; ++k) {
      removeNear(blobs.blobs, slot[k]);
      removeNear(blobs.weak, slot[k]);
    }
  });
  EXPECT_EQ(f.right[0], 8);
  EXPECT_EQ(f.wrong[0], 0);
  EXPECT_EQ(f.right[1] + f.wrong[1], 0);
  EXPECT_LT(f.worst_orientation * 180 / kPi, 1.5);  // 0.51 measured
}

// A peak on the ring much darker than the center blob (JPEG's chroma
// ringing on the black robot top) is no side blob: with one side blob of
// every robot turned that dark, the slot is read from the frame and every
// id is right.
TEST(DetectionSeenColor, DarkPeakIsNoMarker) {
  const RobotsFound f = robotsFoundAfter([](BlobList& blobs, const FieldMm* slot, int n) {
    for (auto& b : blobs.blobs)
      if (std::hypot(b.position.x - slot[1 + n % 4].x, b.position.y - slot[1 + n % 4].y) < 15)
        b.rgb[0] = 25, b.rgb[1] = 45, b.rgb[2] = 30;
  });
  EXPECT_EQ(f.right[0], 8);
  EXPECT_LT(f.right[1], 8);
}

// An over-exposed ball: its top clipped in red and green, its shaded rim
// not. Only the rim's samples count, and their share of the disc says how
// much of it they are; a disc clipped throughout gives nothing.
TEST(DetectionSeenColor, AnOverExposedDiscIsReadWhereItDidNotClip) {
  cv::Mat image(100, 100, CV_8UC3, cv::Scalar(60, 140, 70));  // BGR carpet
  cv::circle(image, {50, 50}, 20, cv::Scalar(40, 120, 220), cv::FILLED);  // rim (r 220, g 120, b 40)
  cv::circle(image, {50, 50}, 12, cv::Scalar(130, 255, 255), cv::FILLED);  // top clipped
  const FrameView frame{&image, BayerPattern::None};
  const SeenColor rim = unclippedDiscColor(frame, {50, 50}, 19);
  ASSERT_GT(rim.share, 0);
  EXPECT_NEAR(rim.rgb[0], 220, 1);
  EXPECT_NEAR(rim.rgb[1], 120, 1);
  EXPECT_NEAR(rim.rgb[2], 40, 1);
  // The ring between radii 12 and 19 is about 60 % of the disc's area.
  EXPECT_NEAR(rim.share, 1 - (12.0 * 12) / (19.0 * 19), 0.12);
  EXPECT_EQ(unclippedDiscColor(frame, {50, 50}, 10).share, 0);
  // Half beyond the image: the share is of the samples inside it.
  EXPECT_GT(unclippedDiscColor(frame, {0, 50}, 19).share, 0);
}

}  // namespace
}  // namespace dv

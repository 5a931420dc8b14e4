// The hypothesis search on hand-placed blobs (detection/hypothesis_search.h):
// which pattern each center blob makes, and how a missing side ranks.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "detection/hypothesis_search.h"
#include "detection_test_scene.h"
#include "geometry/field_model.h"
#include "geometry/robot_pattern.h"

namespace dv {
namespace {

constexpr double kRefHeight = 140;

// Blobs placed directly on the search plane, colors unused: the search
// reads the image only to complete patterns, and there is none here.
class BlobsOnThePlane {
 public:
  int add(const FieldMm& p) {
    FrameBlob b;
    b.at_ref = p;
    b.valid = true;
    b.rgb[0] = b.rgb[1] = b.rgb[2] = 150;
    blobs_.push_back(b);
    return static_cast<int>(blobs_.size()) - 1;
  }
  void setLevel(int i, float level) { blobs_[i].rgb[0] = blobs_[i].rgb[1] = blobs_[i].rgb[2] = level; }
  // The center's blob index; `skip` leaves one side slot (1..4) empty.
  int addRobot(const FieldMm& at, double orientation, int skip = 0) {
    const int c = add(at);
    for (int s = 1; s < kPatternSlots; ++s)
      if (s != skip) add(slotPosition(at, orientation, s));
    return c;
  }
  HypothesisInputs inputs(const ColorVec* colors) {
    index_.points().clear();
    for (const FrameBlob& b : blobs_) index_.points().push_back(b.at_ref);
    index_.build();
    return {&blobs_, static_cast<int>(blobs_.size()), &index_, &weak_, colors, {}};
  }

 private:
  std::vector<FrameBlob> blobs_;
  BlobIndex index_, weak_;
};

struct Search {
  Search() : search(CameraModel(test::topDownCamera())) {
    search.setOptions(DetectorOptions{}, kRefHeight, FieldModel::divisionB().withBoundary());
    for (auto& c : colors) c = colorFeature(100, 100, 100);
  }
  HypothesisSearch search;
  ColorVec colors[color_class::kNumClasses];
};

const Hypothesis* centeredOn(const std::vector<Hypothesis>& hyps, int c) {
  for (const Hypothesis& h : hyps)
    if (h.blob[0] == c) return &h;
  return nullptr;
}

TEST(HypothesisSearch, EachRobotsCenterFitsItsWholePattern) {
  BlobsOnThePlane blobs;
  const FieldMm at[3] = {{1000, 0}, {1600, 400}, {2400, -600}};
  const double orientation[3] = {0.3, -2.0, 2.9};
  int center[3];
  for (int i = 0; i < 3; ++i) center[i] = blobs.addRobot(at[i], orientation[i]);
  Search s;
  std::vector<Hypothesis> hyps;
  s.search.find(blobs.inputs(s.colors), hyps);
  for (int i = 0; i < 3; ++i) {
    const Hypothesis* h = centeredOn(hyps, center[i]);
    ASSERT_NE(h, nullptr) << "robot " << i;
    EXPECT_EQ(h->n, kPatternSlots);
    EXPECT_NEAR(h->pose.position.x, at[i].x, 0.5);
    EXPECT_NEAR(h->pose.position.y, at[i].y, 0.5);
    EXPECT_NEAR(wrapAngle(h->pose.orientation - orientation[i]), 0, 0.01);
    // Each side blob in the slot it was placed in.
    for (int k = 1; k < h->n; ++k) EXPECT_EQ(h->blob[k] - center[i], h->slot[k]) << "robot " << i;
  }
}

TEST(HypothesisSearch, AMissingSideRanksBelowEveryWholePattern) {
  BlobsOnThePlane blobs;
  const int whole = blobs.addRobot({1000, 0}, 0.5);
  const int three = blobs.addRobot({2000, 500}, 1.5, /*skip=*/2);
  Search s;
  std::vector<Hypothesis> hyps;
  s.search.find(blobs.inputs(s.colors), hyps);
  const Hypothesis* a = centeredOn(hyps, whole);
  const Hypothesis* b = centeredOn(hyps, three);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(b->n, kPatternSlots - 1);
  for (int k = 1; k < b->n; ++k) EXPECT_NE(b->slot[k], 2);
  EXPECT_NEAR(wrapAngle(b->pose.orientation - 1.5), 0, 0.01);
  EXPECT_LT(b->rank, a->rank);
  EXPECT_LE(b->rank, 0.5 * b->pose.score + 1e-9);
}

// Peaks far darker than the center lie on the robot's black top (chroma
// ringing around its dots), never on a marker.
TEST(HypothesisSearch, PeaksAsDarkAsARobotTopAreNoSides) {
  for (float side_level : {150.f, 40.f}) {
    BlobsOnThePlane blobs;
    const int c = blobs.addRobot({1500, -300}, -0.8);
    for (int s = 1; s < kPatternSlots; ++s) blobs.setLevel(c + s, side_level);
    Search s;
    std::vector<Hypothesis> hyps;
    s.search.find(blobs.inputs(s.colors), hyps);
    SCOPED_TRACE(side_level);
    EXPECT_EQ(centeredOn(hyps, c) != nullptr, side_level > 150 * kTopBrightness);
  }
}

// Two side blobs alone make a robot only where the frame shows the other
// two markers or the image border hides them: without a frame, no robot.
TEST(HypothesisSearch, TwoSidesWithoutAFrameMakeNone) {
  BlobsOnThePlane blobs;
  const int c = blobs.add({1200, 300});
  blobs.add(slotPosition({1200, 300}, 0.7, 1));
  blobs.add(slotPosition({1200, 300}, 0.7, 3));
  Search s;
  std::vector<Hypothesis> hyps;
  s.search.find(blobs.inputs(s.colors), hyps);
  EXPECT_EQ(centeredOn(hyps, c), nullptr);
}

}  // namespace
}  // namespace dv

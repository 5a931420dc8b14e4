#pragma once
// The detector's state and stages (detector.h), shared by the files that
// hold one stage each: detector.cpp (the frame: blobs in, detections out;
// which hypotheses of hypothesis_search.h become robots), detector_colors.cpp
// (this frame's color classes from its robots -> teams; ids by
// robot_identity.h), detector_tracks.cpp (robot tracks and identity
// hysteresis), detector_balls.cpp (the ball candidates, judged by
// ball_color.h and selected by ball_policy.h). Private to those files.
#include "detection/detector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "detection/ball_color.h"
#include "detection/ball_tracker.h"
#include "detection/blob_index.h"
#include "detection/border_balls.h"
#include "detection/clipped_color.h"
#include "detection/color_classes.h"
#include "detection/fast_streaks.h"
#include "detection/frame_blob.h"
#include "detection/hypothesis_search.h"
#include "detection/pattern_fit.h"
#include "detection/robot_identity.h"
#include "detection/robot_tracker.h"
#include "detection/weak_sides.h"
#include "pipeline/view_stretch.h"

namespace dv {
namespace detector_detail {

using namespace color_class;  // the class ids (ball_color.h)

constexpr int kMaxSlotCandidates = 3;  // blobs per predicted slot (tracking)
// Streak score at which a fast-ball candidate counts at full strength.
constexpr double kStreakFullStrength = 0.6;

inline ColorVec feature(const ColorRef& c) { return colorFeature(c.r, c.g, c.b); }

}  // namespace detector_detail
using namespace detector_detail;

struct Detector::Impl {
  CameraModel camera;
  FieldModel field;
  DetectorOptions opt;
  Eigen::Vector3d cam_pos;
  double ref_height = 140;
  FieldRect ball_area;
  // Whether a ball at p (field mm) lies in ball_area or up to 50 mm
  // beyond it (a ball on the boundary line, measured to its center).
  bool inBallArea(const FieldMm& p) const {
    constexpr double kMargin = 50;
    return p.x >= ball_area.x_min - kMargin && p.x <= ball_area.x_max + kMargin &&
           p.y >= ball_area.y_min - kMargin && p.y <= ball_area.y_max + kMargin;
  }

  ColorClass classes[kNumClasses];
  ColorVec frame_color[kNumClasses];  // this frame's class colors
  bool frame_seen[kNumClasses];       // class had samples in this frame
  float frame_spread[kNumClasses];    // rms distance of its samples to frame_color (0: unknown)
  NeutralColor neutral;               // the lines' color this frame (BlobList::neutral)
  CarpetColor carpet;                 // the carpet beside them (BlobList::carpet)
  float yellow_hue_min = 0;           // of this frame's unclipped yellow centers (learnFrameColors)
  float team_brightness[2] = {0, 0};  // mean r + g + b of this frame's yellow, blue centers (0: none)
  float min_saturation = 0;
  DetectionHealth health;             // of the last frame
  ColorMap color_map;                 // references -> this camera's colors

  std::vector<FrameBlob> blobs;
  std::vector<int> streak_blobs;  // indices into blobs, for the unpeaked-center search
  BlobIndex index;       // the blobs
  BlobIndex weak_index;  // the weak peaks, blob n_strong + i at point i
  int n_strong = 0;
  std::vector<Hypothesis> hyps;
  std::vector<Hypothesis> robots;  // accepted
  RobotTracker tracker;
  BallTracker ball_tracker;
  FastStreaks fast_streaks;  // blobs no color rule took, of the last frames
  std::vector<FieldMm> robot_positions;  // of the accepted robots, for the ball tracker
  std::vector<BallCandidate> ball_cands;
  std::vector<ColorVec> samples;
  // Each sample's RGB, which clusterSpread judges (ClippedColor: a clipped
  // sample lies from its class as far as the nearest color that clips to
  // it; the pale chroma of centers clipped in red and green widened the
  // yellow class's reach over the carpet beside a ball of its color).
  std::vector<std::array<float, 3>> sample_rgb;
  void addSample(const float rgb[3]);
  std::vector<uint8_t> labels;
  std::vector<float> score_buf;
  double last_t = 0;
  double frame_interval = 0;  // between the last two related frames, s
  void expectedBalls(ExpectedPlaces& out) const;
  bool have_frame = false;
  bool new_scene = false;  // this frame dropped the history (unrelated scene)

  Impl(const CameraModel& cam, const FieldModel& f, const DetectorOptions& o);

  // Takes new options between frames; tracks and learned colors stay.
  void setOptions(const DetectorOptions& o);

  void reset();

  double teamHeight(Team t) const {
    return t == Team::Yellow ? opt.robot_height_yellow : opt.robot_height_blue;
  }

  // Moves a point along its camera ray from plane z0 to plane z1. This is
  // exactly fieldToImage followed by imageToField (the ray does not depend
  // on the lens distortion), without the distortion solve per blob.
  bool alongRay(const FieldMm& p, double z0, double z1, FieldMm& out) const {
    const double cz = cam_pos.z();
    if (cz <= z0 + 1 || cz <= z1 + 1) return false;
    const double s = (cz - z1) / (cz - z0);
    out = {cam_pos.x() + s * (p.x - cam_pos.x()), cam_pos.y() + s * (p.y - cam_pos.y())};
    return true;
  }

  // ---------------------------------------------------------------- frame
  void prepare(const BlobList& list);
  // Fills f's unclipped color where blob b (on plane z0) clips in two channels.
  void readUnclipped(const Blob& b, double z0, FrameBlob& f) const;
  static bool readByRim(const FrameBlob& b);
  // A center's color: clipped in all three channels, its rim's where it
  // has one (readByRim), else its own.
  static const float* centerRgb(const FrameBlob& b);

  // ------------------------------------------- position based hypotheses
  HypothesisSearch search;
  HypothesisInputs searchInputs(const ColorVec* colors) {
    return {&blobs, n_strong, &index, &weak_index, colors, frame_view};
  }

  // Whether `pose` overlaps an accepted robot's top (other than `skip`).
  bool overlapsAccepted(const PatternPose& pose, const Hypothesis* skip = nullptr) const;

  void selectRobots();

  // Centers left without a robot that look like this frame's yellow or
  // blue rather than any other class it learned: searched again against
  // the frame's colors (the first search judged unpeaked markers by the
  // retained classes, which in a frame alone are the fixed references: a
  // pale rose dot reads as neither green nor pink against those). Robots
  // found so join `robots` with the nearer team color. Returns how many.
  // Weak peaks are searched too, as centers beside a free side-colored
  // blob that their pattern then holds.
  int searchAgainWithFrameColors();
  // Whether `seen` is nearer to this frame's yellow or blue than to any
  // other class it learned (clipped channels as ClippedColor reads them);
  // `team`, where given, is set to the nearer team.
  bool teamColored(const ClippedColor& seen, Team* team = nullptr) const;
  // The same for green or pink: a marker of a robot's side.
  bool sideColored(const ClippedColor& seen) const;
  // The team of a center whose four side blobs all peaked: the pattern is
  // the robot's evidence, so its center need only be nearer to yellow or
  // blue than to the field (over-exposure washes a lemon center nearer to
  // the lines' white, and to the side colors, than to either team), where
  // the frame showed centers of both teams (else teamColored). One
  // clipped in all three channels has no hue left, only its brightness:
  // it is of the team whose centers this frame shows brighter.
  bool teamOfFullPattern(const ClippedColor& seen, Team* team) const;
  // Robots whose center made no blob: the pixel stage's color gate judges
  // a center against the lines' white, and a pale center clipped in two
  // channels (sky blue in a sun patch, (150, 255, 255) beside lines of
  // (160, 220, 255)) is as little saturated as a line crossing. Where free
  // side blobs (min_side_blobs of them) fit the pattern tightly
  // (min_weak_fit) around a place where no blob peaked or only one no
  // robot holds, the center's color is read from the frame there: as bright
  // as a marker and team-colored (teamColored; teamOfFullPattern with four
  // sides), it is the robot, its center that blob or one appended to
  // `blobs`.
  // Returns how many robots joined `robots`.
  int robotsAroundUnpeakedCenters();
  // Robots of which only a side dot peaked: over-exposed under uneven
  // light, pale centers and pinks wash toward the lines' white and keep
  // too little chroma to peak, while a green keeps it (extreme #40: three
  // robots, each one green blob). Around a free green or pink blob the
  // center is the brightest place on the circle of the side distance;
  // where no blob peaked there, it reads team-colored (teamColored) and it
  // lies on a dark top (kDotOverTop times the ring's darkest point: a
  // sun-lit carpet's texture is bright all round), a center blob is
  // appended there and the search judges it as any center
  // (HypothesisSearch::bestAt: with one side blob, every other slot must
  // show a marker). Returns how many robots joined `robots`.
  int robotsAroundLoneSides();
  // Where the searches found one team only, the other may be there with
  // centers that no class places (sky blue under a warm cast at saturation
  // 0.5 reads as gray as the lines). The full patterns around such
  // unclipped centers are probed (probing_unseen_team:
  // robotsAroundUnpeakedCenters takes them without a team, and they are
  // undone after). Where the centers split in two (clusterCenters from the
  // unclipped ones), the probed ones all in one cluster, most of the seen
  // team's in the other, and the probed cluster on the unseen team's side
  // of the lines' white (as orderByRatio; of the seen team's color where
  // every one of its centers clipped), that cluster is this frame's color
  // of the unseen team.
  void learnUnseenTeam();
  bool probing_unseen_team = false;
  // Side blobs a (slot sa) and b (slot sb) with the free blobs partner[0, k)
  // in the other slots; the pattern `h` (slots 1.. filled; the center's
  // color read into center_rgb) where it passes robotsAroundUnpeakedCenters'
  // tests.
  bool patternAroundSides(int a, int sa, int b, int sb, const int* partner, int k, Hypothesis& h,
                          float center_rgb[3]);
  // A center blob read from the frame at `at_ref` (search plane).
  FrameBlob centerBlobAt(const FieldMm& at_ref, const float rgb[3]) const;

  // ------------------------------------------------------ color classes
  // Clutter (carpet noise, line crossings) can line up like a pattern. A
  // robot's center must look like this frame's yellow or blue rather than
  // like the field or a white line; the team colors come from clustering
  // the centers first, so no fixed hue is involved.
  // color_classes.h's orderByRatio over `samples` and `labels`, against
  // the lines' white of this frame.
  void orderByRatio(TwoMeansResult& r, int num, int den);
  // Center blob colors of the robot hypotheses in two classes, yellow vs
  // blue, with this frame's green and pink (splitSides) as the external
  // colors (eq. 5.24). Each robot's cluster (0 yellow, 1 blue) is left in
  // `center_labels`; `samples` and `labels` hold the centers the split was
  // learned from. A center clipped in two channels shows a hue it need not
  // have (an amber center clipped in red and green reads as pale as the
  // lines): `from_unclipped`, the split is learned from the other centers
  // where there are any, and each clipped one joins the mean nearer to the
  // colors it may have been (ClippedColor).
  TwoMeansResult clusterCenters(bool from_unclipped = false);
  std::vector<uint8_t> center_labels;
  // centerRgb as ClippedColor judges it.
  static ClippedColor centerSeen(const FrameBlob& b);
  // Whether one cluster of a split of the centers is the other's color
  // clipped: most of its centers clipped, each within the other's reach
  // (classReach) of a color that clips to it (ClippedColor). An amber team
  // clipped in red and green in the brighter half reads as pale as the
  // lines and splits from its unclipped half as the bluer cluster; a
  // clipped sky blue is no clipped yellow. (A stray unclipped center may
  // join the clipped ones: a first-pass robot of its center alone did.)
  bool splitByClipping(const TwoMeansResult& r) const;
  // The robots' side blobs (weak peaks aside: too noisy to learn from) in
  // two classes, green vs pink, the team colors `ext` as external; the
  // samples and labels are left in `samples` and `labels`.
  TwoMeansResult splitSides(const ColorVec ext[2]);

  // Drops the robots i for which drop(i) holds, in place, freeing their
  // blobs (and marking their centers implausible where `implausible`: no
  // later search takes them for centers); returns how many.
  template <class Drop>
  int dropRobots(Drop drop, bool implausible);
  // Drops the robots whose center looks like the field or a line more than
  // like its team's color, marks those centers implausible, and returns how
  // many were dropped.
  int dropImplausibleCenters();

  // Classes a and b from twoMeans's clusters 0 and 1 (over `samples`,
  // `labels`): this frame's color, its spread, and the class it retains.
  void learnClass(int a, int b, const TwoMeansResult& r);
  void learnClassFrom(int cls, const TwoMeansResult& r, int label);
  // The rms distance of cluster `label`'s samples to its mean: how far a
  // color may lie from the class and still be it (classReach).
  float clusterSpread(const TwoMeansResult& r, int label) const;
  // Drops the robots that are a center alone (its dots all read from the
  // frame) where two markings cross: the crossing's four arms are what the
  // frame shows at the slots.
  void dropCentersAloneAtCrossings();

  // One robot per team and id in a frame: of two, the less sure (a guessed
  // id before a read one) is wrong, and is dropped, its blobs freed for the
  // ball (moderate #329: a sun-lit ball among carpet peaks made a second
  // yellow 8, at 0.19 beside the real one's 0.95, and no ball).
  void dropSecondIds();
  std::vector<uint8_t> second_id;  // per robot: another holds its id

  // Drops the robots of a center and at most one side blob whose center
  // is nearer this frame's green or pink (learned from the side blobs)
  // than its own team's color: a side dot taken for a center (a robot on
  // a line whose pale pinks made no peak, its green beside its center);
  // the center is marked implausible and its blobs freed for the second
  // search.
  void dropDotsTakenForCenters();
  // This frame's class colors from its robots: the centers split into
  // yellow and blue (each robot's team), the side blobs into green and
  // pink; frame_color holds them (the retained class where a class had no
  // samples).
  void learnFrameColors();
  // Each robot's id (robot_identity.h), the ids teammates rule out
  // (partial_ids.h), and the camera's color map.
  void identifyRobots();

  // Where no side blob of this frame is pink (pale dots that peak as none,
  // clipped toward the lines' white), the pink class would be only what
  // earlier frames or the reference say: the colors the frame shows at the
  // robots' unfilled slots (as bright as markers) are clustered with the
  // side blobs (in `samples`), and a cluster redder than the lines' white
  // (orderByRatio) is this frame's pink.
  void pinkFromUnseenSlots();

  // refitAtTeamHeight (robot_identity.h) over this frame's blobs.
  void refit(Hypothesis& h) const;

  int weakCount(const Hypothesis& h) const {
    int n = 0;
    for (int i = 0; i < h.n; ++i) n += blobs[h.blob[i]].weak;
    return n;
  }

  int nearestOf(const ColorVec& c, int a, int b) const {
    return colorDistance(c, frame_color[a]) <= colorDistance(c, frame_color[b]) ? a : b;
  }

  // ----------------------------------------------------------- tracking
  // The robot tracker (robot_tracker.h) over this frame's robots; a frame
  // that shows an unrelated scene drops the ball tracks too.
  void track(double t);

  // A track no robot of this frame continued: two or more of its blobs
  // around the predicted blob positions (§5.3.6), colors agreeing with its
  // identity, make a robot appended to `out`.
  bool recoverTrack(const RobotTrack& tr, int k, std::vector<Hypothesis>& out);

  // --------------------------------------------------------------- balls
  void findBalls(double t, bool tracking, Detections& out);
  // Whether the ball color around blob i reaches beyond one ball's rim
  // (ballColorBeyondRim). A color no class explains is
  // a ball of an unexpected shade only where it lies on a disc: the Bayer
  // mosaic's false colors along thin lines (1 to 2 px wide at
  // 1224 x 1024) make a line crossing a blob of a color near none, and
  // that color runs on along the lines (a third to a half of a disc beyond
  // the rim; a ball alone shows none). False where the frame is not at
  // hand.
  bool colorReachesBeyondRim(int i, const BallColorTest& judge) const;
  // Whether blob i shows one whole ball's silhouette in `judge`'s colors
  // (ballSilhouetteCenter). False where the frame is not at hand.
  bool wholeBallSilhouette(int i, const BallColorTest& judge) const;
  // Blob i seen as a ball: its place in the image (on the ball plane's
  // image of its raw position) and the ball's radius there (px); false
  // where the frame is not at hand or the camera does not see it.
  bool ballInImage(int i, ImagePx& px, double& radius_px) const;
  // Round blobs in a marker's color (yellow or pink) outside every robot,
  // with that class: the ball where no blob or border fit of the ball's
  // own colors is (marker_colored_ball.h). Appends the surest of those
  // standing alone on the carpet to ball_cands.
  struct MarkerColoredBlob {
    int blob;
    int cls;
    ColorVec around;      // the ring's color (colorAroundBall)
    bool has_around = false;
  };
  std::vector<MarkerColoredBlob> marker_colored;
  void addMarkerColoredBalls(const BallColorTest& judge, double strength_ref, bool tracking);
  // Peaks the pixel stage's color gate dropped as clipped pale (BlobList::
  // pale): the ball where no other is, where they show one whole ball's
  // disc standing out from the carpet around it, off the markings and
  // every robot (detector_pale_balls.cpp). Appends the surest to
  // ball_cands.
  std::vector<Blob> pale;
  void addPaleBalls(double strength_ref, bool tracking);
  // A fallback's candidate judged by where it lies (`carpet`: the share of
  // its ring that is carpet; `score`: its peak's): confidence and rank
  // from both and its track, kept where it is the fallback's surest so far
  // (`best`: its index in ball_cands, -1 before the first). One ball at
  // most: a sun patch's lit carpet makes many peaks alike.
  void keepSurest(BallCandidate c, double carpet, double score, double strength_ref, bool tracking, int& best);
  // Rules: at least 80 % of a ball at p (ball plane) is outside every
  // robot's top. Nor is a blob a ball where its picture lies on a robot's
  // top, read on the top's plane (`at_team`, the blob at the yellow and
  // blue heights, where given): the top stands between whatever lies below
  // and the camera (a robot's pale pink dot by the image's edge, left over
  // by its pattern, lay 133 mm from its center on the ball's plane).
  bool insideAnyRobot(const FieldMm& p, const FieldMm* at_team) const;
  // The ball candidate's temporal consistency: 1 where it continues a ball
  // track (or tracking is off), else less. Matches c to its track.
  double ballTemporal(BallCandidate& c, bool tracking);
  // How surely a candidate ballTemporal matched continues its track on its
  // course, one moving faster than any robot: 1 at the prediction, 0 at the
  // gate's edge; 0 off every such course.
  double courseConfidence(const BallCandidate& c) const;
  // Where the camera's ray through ball-plane point p is at height z.
  FieldMm seenAtHeight(const FieldMm& p, double z) const;
  // Whether `p` (ball plane) lies within a ball radius of a field marking's
  // or of a goal wall's center line, or its ray passes that near one where
  // the marking lies or the wall stands, and whether the camera sees it
  // stretched (a grazing view, view_stretch.h).
  bool onMarking(const FieldMm& p) const;
  bool atCrossing(const FieldMm& p) const;  // within that of two markings
  bool onGoalWall(const FieldMm& p) const;
  bool seenStretched(const FieldMm& p) const;
  // This frame's colors for the ball's color judge (ball_color.h).
  FrameColors ball_colors;
  // The same with the field as the carpet beside the lines shows it, for
  // the ring around a ball (carpetAroundBall). The field class learns from
  // the carpet's clutter peaks, which a frame may lack: under tungsten at
  // saturation 0.4 with a sun patch over the ball it was still its
  // reference, 52 from the carpet, the teams' classes lay nearer, and the
  // lit ring around the ball counted as no carpet.
  FrameColors ring_colors;

  std::vector<FieldMm> raw_positions;  // per blobs[] entry, on the rectification plane
  double plane_height = 150;

  // Balls cut by the image border (border_balls.h), found in the frame;
  // the finder is made for the ball radius it was built with.
  std::optional<BorderBallFinder> border_finder;
  std::vector<BorderBall> border_balls;

  FrameView frame_view;  // the frame being processed (may be empty)

  void process(const BlobList& list, double t, Detections& out, const FrameView& frame);
};

}  // namespace dv

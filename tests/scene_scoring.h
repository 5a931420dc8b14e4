#pragma once
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
// Scoring rendered scenes end to end (renderer -> CPU pixel pipeline ->
// detector) against the renderer's truth, shared by the scene tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "detection/detector.h"
#include "geometry/robot_pattern.h"
#include "pipeline/cpu_pipeline.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv::test {

struct SceneScore {
  int truth_robots = 0, matched = 0, id_ok = 0, detected = 0;
  int truth_balls = 0, balls_matched = 0, balls_detected = 0;
  // Objects whose blobs reached the detector (center + 4 sides for robots:
  // with 3 the id is one of two and a guess is not reported; a blob for the
  // ball): what blob assignment alone can be held to.
  int detectable_robots = 0, detectable_matched = 0, detectable_balls = 0,
      detectable_balls_matched = 0;
  // Robots whose center and all four side blobs reached the detector, and
  // how many of those got the right team and id.
  int full_robots = 0, full_id_ok = 0;
  std::vector<double> pos_err, ang_err, ball_err;

  double recall() const { return truth_robots ? double(matched) / truth_robots : 1; }
  double precision() const { return detected ? double(matched) / detected : 1; }
  double idAccuracy() const { return matched ? double(id_ok) / matched : 1; }
  double ballRecall() const { return truth_balls ? double(balls_matched) / truth_balls : 1; }
  double ballPrecision() const { return balls_detected ? double(balls_matched) / balls_detected : 1; }
  double detectableRecall() const {
    return detectable_robots ? double(detectable_matched) / detectable_robots : 1;
  }
  double fullPatternIdAccuracy() const { return full_robots ? double(full_id_ok) / full_robots : 1; }
  double detectableBallRecall() const {
    return detectable_balls ? double(detectable_balls_matched) / detectable_balls : 1;
  }
  static double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  }
  std::string summary(const std::string& name) const {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "%s: robots %d/%d recall %.4f precision %.4f id %.4f pos med %.2f mm ang med "
                  "%.3f deg | balls %d/%d recall %.4f precision %.4f err med %.2f mm | blobs "
                  "complete: robots %d/%d balls %d/%d",
                  name.c_str(), matched, truth_robots, recall(), precision(), idAccuracy(),
                  median(pos_err), median(ang_err) * 180 / kPi, balls_matched, truth_balls,
                  ballRecall(), ballPrecision(), median(ball_err), detectable_matched,
                  detectable_robots, detectable_balls_matched, detectable_balls);
    return buf;
  }
};

// Halves a camera's resolution (focal length, principal point, size).
inline void halveResolution(SceneSpec& spec) {
  for (auto& c : spec.cameras) {
    auto& k = c.calib;
    k.focal_length /= 2;
    k.principal_point_x = (k.principal_point_x + 0.5) / 2 - 0.5;
    k.principal_point_y = (k.principal_point_y + 0.5) / 2 - 0.5;
    k.image_width /= 2;
    k.image_height /= 2;
  }
}

inline bool fullRun() {
  const char* e = std::getenv("DV_SCENE_FULL");
  return e && std::string(e) == "1";
}

// The pipeline's reading of the frames `spec` renders.
inline BayerPattern pipelineBayer(const SceneSpec& spec) {
  if (!spec.bayer) return BayerPattern::None;
  switch (spec.bayer_layout) {
    case BayerLayout::RGGB: return BayerPattern::RGGB;
    case BayerLayout::GRBG: return BayerPattern::GRBG;
    case BayerLayout::GBRG: return BayerPattern::GBRG;
    case BayerLayout::BGGR: return BayerPattern::BGGR;
  }
  return BayerPattern::RGGB;
}

// Where a point at height z appears on the blob plane: the camera's ray
// through it, met with the plane the grid lies on.
inline FieldMm onBlobPlane(const CameraModel& cam, const BlobList& blobs, double x, double y, double z) {
  const Eigen::Vector3d cpos = cam.position();
  const double k = (cpos.z() - blobs.plane_height) / (cpos.z() - z);
  return {cpos.x() + k * (x - cpos.x()), cpos.y() + k * (y - cpos.y())};
}

// With DV_DUMP=DIR: a crop of the frame around field point `p`, 4x
// enlarged, as DIR/<name>.png.
inline void dumpCrop(const cv::Mat& image, const CameraModel& cam, const FieldPoint& p, const std::string& name) {
  const char* dir = std::getenv("DV_DUMP");
  const auto px = cam.fieldToImage(p);
  if (!dir || !px) return;
  cv::Mat bgr = image;
  if (image.channels() == 1) cv::cvtColor(image, bgr, cv::COLOR_BayerBG2BGR);  // the renderer's RGGB
  const int r = 60 * bgr.cols / 1224;
  const cv::Rect box = cv::Rect(static_cast<int>(px->u) - r, static_cast<int>(px->v) - r, 2 * r, 2 * r) &
                       cv::Rect(0, 0, bgr.cols, bgr.rows);
  cv::Mat crop;
  cv::resize(bgr(box), crop, {}, 4, 4, cv::INTER_NEAREST);
  cv::imwrite(std::string(dir) + "/" + name + ".png", crop);
}

// What a sweep saw of a robot it lost (DV_MISSES): the blobs, weak and
// pale peaks within 150 mm of it and where its five blobs should lie on the
// blob plane; with DV_DUMP=DIR also a crop of the frame around it, DIR/
// miss_<width>_<id>_<x>_<y>.png.
template <class Truth>
void printMiss(const Truth& t, const cv::Mat& image, const CameraModel& cam, const BlobList& blobs) {
  auto onPlane = [&](double x, double y) { return onBlobPlane(cam, blobs, x, y, t.height()); };
  const FieldMm c = onPlane(t.x(), t.y());
  std::printf("  center expected at (%.0f, %.0f), sides at", c.x, c.y);
  const double cs = std::cos(t.orientation()), sn = std::sin(t.orientation());
  for (const auto& o : RobotPatternGeometry::kSideBlobs) {
    const FieldMm p = onPlane(t.x() + cs * o.x - sn * o.y, t.y() + sn * o.x + cs * o.y);
    std::printf(" (%.0f, %.0f)", p.x, p.y);
  }
  std::printf("\n");
  const std::vector<Blob>* lists[3] = {&blobs.blobs, &blobs.weak, &blobs.pale};
  const char* names[3] = {"blob", "weak peak", "pale peak"};
  for (int w = 0; w < 3; ++w)
    for (const auto& b : *lists[w])
      if (std::hypot(b.position.x - c.x, b.position.y - c.y) < 150)
        std::printf("  %s at (%.0f, %.0f), score %.2f, rgb %.0f %.0f %.0f\n", names[w], b.position.x,
                    b.position.y, b.score, b.rgb[0], b.rgb[1], b.rgb[2]);
  dumpCrop(image, cam, {t.x(), t.y(), t.height()},
           "miss_" + std::to_string(image.cols) + "_" + std::to_string(t.robot_id()) + "_" +
               std::to_string(static_cast<int>(t.x())) + "_" + std::to_string(static_cast<int>(t.y())));
}

// Runs `frames` frames of `spec` (camera 0). `alone`: every frame is
// detected without history (reset before each). `detect_with`: the
// calibration the processor uses, when not the one rendered (a fit of it).
inline void score(const SceneSpec& spec, int frames, bool alone, SceneScore& s,
                  const CameraCalibration* detect_with = nullptr) {
  Renderer renderer(spec);
  const CameraModel cam(detect_with ? *detect_with : spec.cameras[0].calib);
  PipelineOptions popt;
  popt.bayer = pipelineBayer(spec);
  CpuPipeline pipeline(cam, spec.field, popt);
  DetectorOptions dopt;
  dopt.tracking = !alone;
  Detector detector(cam, spec.field, dopt);
  BlobList blobs;
  Detections out;
  for (int f = 0; f < frames; ++f) {
    const RenderedFrame frame = renderer.render(f, 0);
    ASSERT_TRUE(pipeline.process(frame.image, blobs)) << pipeline.lastError();
    if (alone) detector.reset();
    detector.process(blobs, frame.truth.t_capture(), out, FrameView{&frame.image, popt.bayer});

    // Blobs near where a point at height z appears on the blob plane
    // (streak blobs only for balls: they are never part of a robot).
    auto blobNear = [&](double x, double y, double z, double tol, bool ball = false) {
      const FieldMm p = onBlobPlane(cam, blobs, x, y, z);
      for (const auto& b : blobs.blobs)
        if ((ball || !b.streak) && std::hypot(b.position.x - p.x, b.position.y - p.y) < tol) return true;
      return false;
    };
    // Side blobs seen of a robot whose center blob was seen, else -1.
    auto sidesSeen = [&](const auto& t) {
      if (!blobNear(t.x(), t.y(), t.height(), 12)) return -1;
      int sides = 0;
      const double cs = std::cos(t.orientation()), sn = std::sin(t.orientation());
      for (const auto& o : RobotPatternGeometry::kSideBlobs)
        sides += blobNear(t.x() + cs * o.x - sn * o.y, t.y() + sn * o.x + cs * o.y, t.height(), 12);
      return sides;
    };
    std::vector<bool> used(out.robots.size(), false);
    s.detected += static_cast<int>(out.robots.size());
    auto matchTeam = [&](const auto& list, Team team) {
      for (const auto& t : list) {
        ++s.truth_robots;
        const int sides = sidesSeen(t);
        const bool complete = sides == 4;
        s.detectable_robots += complete;
        s.full_robots += sides == 4;
        int best = -1;
        double best_d = 60;
        for (size_t i = 0; i < out.robots.size(); ++i) {
          const double d =
              std::hypot(out.robots[i].position.x - t.x(), out.robots[i].position.y - t.y());
          if (!used[i] && d < best_d) best_d = d, best = static_cast<int>(i);
        }
        if (best < 0) {
          if (std::getenv("DV_MISSES"))  // which robots a sweep lost, and how many side blobs it had
            std::printf("missed: %s %u at (%.0f, %.0f), side blobs seen %d\n",
                        team == Team::Yellow ? "yellow" : "blue", t.robot_id(), t.x(), t.y(), sides);
          if (std::getenv("DV_MISSES")) printMiss(t, frame.image, cam, blobs);
          continue;
        }
        used[best] = true;
        ++s.matched;
        s.detectable_matched += complete;
        const auto& r = out.robots[best];
        if (r.team == team && r.id == static_cast<int>(t.robot_id())) {
          ++s.id_ok;
          s.full_id_ok += sides == 4;
        } else if (std::getenv("DV_MISSES")) {
          std::printf("wrong id: %s %u at (%.0f, %.0f) reported as %s %d, side blobs seen %d, orientation %.1f deg "
                      "(true %.1f)\n",
                      team == Team::Yellow ? "yellow" : "blue", t.robot_id(), t.x(), t.y(),
                      r.team == Team::Yellow ? "yellow" : "blue", r.id, sides, r.orientation * 180 / kPi,
                      t.orientation() * 180 / kPi);
          printMiss(t, frame.image, cam, blobs);
        }
        s.pos_err.push_back(best_d);
        s.ang_err.push_back(std::abs(std::remainder(r.orientation - t.orientation(), 2 * kPi)));
      }
    };
    matchTeam(frame.truth.robots_yellow(), Team::Yellow);
    matchTeam(frame.truth.robots_blue(), Team::Blue);
    for (size_t i = 0; i < out.robots.size(); ++i)  // robots reported where none is (DV_MISSES)
      if (!used[i] && std::getenv("DV_MISSES"))
        std::printf("false robot: %s %d at (%.0f, %.0f), orientation %.1f deg, confidence %.2f\n",
                    out.robots[i].team == Team::Yellow ? "yellow" : "blue", out.robots[i].id,
                    out.robots[i].position.x, out.robots[i].position.y, out.robots[i].orientation * 180 / kPi,
                    out.robots[i].confidence);

    s.balls_detected += static_cast<int>(out.balls.size());
    for (const auto& b : frame.truth.balls()) {
      ++s.truth_balls;
      const bool complete = blobNear(b.x(), b.y(), b.z(), 15, true);
      s.detectable_balls += complete;
      bool matched = false;
      for (const auto& d : out.balls) {
        const double e = std::hypot(d.position.x - b.x(), d.position.y - b.y());
        if (e < 50) {
          ++s.balls_matched;
          s.detectable_balls_matched += complete;
          s.ball_err.push_back(e);
          matched = true;
          break;
        }
      }
      if (!matched && std::getenv("DV_MISSES")) {
        std::printf("missed: ball at (%.0f, %.0f), a blob there %s\n", b.x(), b.y(), complete ? "yes" : "no");
        const FieldMm p = onBlobPlane(cam, blobs, b.x(), b.y(), b.z());
        for (const auto& bl : blobs.blobs)
          if (std::hypot(bl.position.x - p.x, bl.position.y - p.y) < 15)
            std::printf("  blob score %.2f, rgb %.0f %.0f %.0f%s\n", bl.score, bl.rgb[0], bl.rgb[1], bl.rgb[2],
                        bl.streak ? " (streak)" : "");
        ColorVec classes[Detector::kClassColorCount];
        detector.classColors(classes);
        std::printf("  classes (chromaticity):");
        for (int c = 0; c < Detector::kClassColorCount; ++c)
          std::printf(" %s %.0f %.0f %.0f;", Detector::classColorName(c), classes[c].c[0], classes[c].c[1],
                      classes[c].c[2]);
        std::printf(" lines rgb %.0f %.0f %.0f\n", blobs.neutral.rgb[0], blobs.neutral.rgb[1], blobs.neutral.rgb[2]);
      }
    }
    // Balls reported where no ball is (DV_MISSES).
    for (const auto& d : out.balls) {
      bool real = false;
      for (const auto& b : frame.truth.balls()) real |= std::hypot(d.position.x - b.x(), d.position.y - b.y()) < 50;
      if (real || !std::getenv("DV_MISSES")) continue;
      std::printf("false ball at (%.0f, %.0f), confidence %.2f\n", d.position.x, d.position.y, d.confidence);
      const double ball_z = spec.field.ball_radius;  // a ball resting on the carpet
      const FieldMm at = onBlobPlane(cam, blobs, d.position.x, d.position.y, ball_z);
      for (const auto& b : blobs.blobs)
        if (std::hypot(b.position.x - at.x, b.position.y - at.y) < 60)
          std::printf("  blob at (%.0f, %.0f), score %.2f, rgb %.0f %.0f %.0f%s\n", b.position.x, b.position.y,
                      b.score, b.rgb[0], b.rgb[1], b.rgb[2], b.streak ? ", a streak" : "");
      dumpCrop(frame.image, cam, {d.position.x, d.position.y, ball_z},
               "false_ball_" + std::to_string(frame.image.cols) + "_" + std::to_string(static_cast<int>(d.position.x)) +
                   "_" + std::to_string(static_cast<int>(d.position.y)));
    }
  }
}

}  // namespace dv::test

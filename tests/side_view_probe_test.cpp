// Diagnostic (not part of the suite's bars): per robot of the side-view
// placements, distance, dot sizes in image pixels and the blobs found at
// its five slots. Run with --gtest_also_run_disabled_tests.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "scene_scoring.h"

namespace dv {
namespace {

using test::pipelineBayer;

TEST(SideViewProbe, DISABLED_PerRobot) {
  const int placements = 6;
  int missed = 0, total = 0;
  for (int k = 0; k < placements; ++k) {
    SceneSpec spec = presetScene("side_view");
    if (k > 0) {
      spec.seed += k;
      const int n = static_cast<int>(spec.robots.size()) / 2;
      spec.robots.clear();
      spec.robots = placeRandomRobots(spec, 0, n, n, spec.seed, 200, 30);
    }
    Renderer renderer(spec);
    const CameraModel cam(spec.cameras[0].calib);
    PipelineOptions popt;
    popt.bayer = pipelineBayer(spec);
    CpuPipeline pipeline(cam, spec.field, popt);
    PipelineOptions low = popt;
    low.threshold = 0.06;
    low.weak_threshold = 0;
    CpuPipeline probe(cam, spec.field, low);
    DetectorOptions dopt;
    dopt.tracking = false;
    Detector detector(cam, spec.field, dopt);
    BlobList blobs, low_blobs;
    Detections out;
    const RenderedFrame frame = renderer.render(0, 0);
    ASSERT_TRUE(pipeline.process(frame.image, blobs));
    ASSERT_TRUE(probe.process(frame.image, low_blobs));
    detector.process(blobs, frame.truth.t_capture(), out);
    if (k == 0)
      std::printf("grid scale %.2f mm, %s, gradient %.2f cells, quadrant %d cells\n", pipeline.grid().scale,
                  pipeline.samplingNote().c_str(), pipeline.gradientScale(), pipeline.quadrantRadius());
    const Eigen::Vector3d c = cam.position();
    auto onPlane = [&](double x, double y, double z) {
      const double s = (c.z() - blobs.plane_height) / (c.z() - z);
      return FieldMm{c.x() + s * (x - c.x()), c.y() + s * (y - c.y())};
    };
    // Image extent of a disc of radius r at (x, y, z): along the ground
    // direction from the camera and across it.
    auto extent = [&](double x, double y, double z, double r, double& along, double& across) {
      const double dx = x - c.x(), dy = y - c.y(), d = std::hypot(dx, dy);
      const double ux = dx / d, uy = dy / d;
      auto px = [&](double ox, double oy) { return cam.fieldToImage({x + ox, y + oy, z}); };
      const auto a0 = px(-r * ux, -r * uy), a1 = px(r * ux, r * uy);
      const auto b0 = px(r * uy, -r * ux), b1 = px(-r * uy, r * ux);
      along = a0 && a1 ? std::hypot(a1->u - a0->u, a1->v - a0->v) : -1;
      across = b0 && b1 ? std::hypot(b1->u - b0->u, b1->v - b0->v) : -1;
    };
    auto nearest = [&](const std::vector<Blob>& list, FieldMm p, double tol) -> const Blob* {
      const Blob* best = nullptr;
      double bd = tol;
      for (const auto& b : list) {
        const double d = std::hypot(b.position.x - p.x, b.position.y - p.y);
        if (!b.streak && d < bd) bd = d, best = &b;
      }
      return best;
    };
    std::vector<bool> used(out.robots.size(), false);
    auto run = [&](const auto& list, Team team) {
      for (const auto& t : list) {
        ++total;
        int best = -1;
        double bd = 60;
        for (size_t i = 0; i < out.robots.size(); ++i) {
          const double d = std::hypot(out.robots[i].position.x - t.x(), out.robots[i].position.y - t.y());
          if (!used[i] && d < bd) bd = d, best = static_cast<int>(i);
        }
        if (best >= 0) used[best] = true;
        const bool ok = best >= 0;
        missed += !ok;
        const double dist = std::hypot(t.x() - c.x(), t.y() - c.y());
        double al, ac, sal, sac;
        extent(t.x(), t.y(), t.height(), 25, al, ac);
        const double cs = std::cos(t.orientation()), sn = std::sin(t.orientation());
        const auto& o0 = RobotPatternGeometry::kSideBlobs[0];
        extent(t.x() + cs * o0.x - sn * o0.y, t.y() + sn * o0.x + cs * o0.y, t.height(), 20, sal, sac);
        std::printf("%d %s id %2d %s%s d %.0f mm (%.0f,%.0f) center %.1fx%.1f side %.1fx%.1f px | ", k,
                    team == Team::Yellow ? "Y" : "B", static_cast<int>(t.robot_id()), ok ? "ok  " : "MISS",
                    ok && out.robots[best].id != static_cast<int>(t.robot_id()) ? "(id)" : "", dist, t.x(), t.y(), al,
                    ac, sal, sac);
        for (int s = 0; s < 5; ++s) {
          double x = t.x(), y = t.y();
          if (s > 0) {
            const auto& o = RobotPatternGeometry::kSideBlobs[s - 1];
            x += cs * o.x - sn * o.y, y += sn * o.x + cs * o.y;
          }
          const FieldMm p = onPlane(x, y, t.height());
          if (!ok) {
            const auto ip = cam.fieldToImage({x, y, t.height()});
            if (ip) std::printf("[%.0f,%.0f]", ip->u, ip->v);
          }
          const Blob* b = nearest(blobs.blobs, p, 12);
          const Blob* w = b ? nullptr : nearest(blobs.weak, p, 12);
          const Blob* l = b || w ? nullptr : nearest(low_blobs.blobs, p, 12);
          const Blob* f = b ? b : w ? w : l;
          const char tag = b ? 'S' : w ? 'w' : l ? 'l' : '-';
          if (!f) {
            const auto ip = cam.fieldToImage({x, y, t.height()});
            if (ip) {
              const auto e = cam.imageToField({2447.5, ip->v}, t.height());
              const auto e0 = cam.imageToField({-0.5, ip->v}, t.height());
              const auto eb = cam.imageToField({ip->u, 2047.5}, t.height());
              std::printf("{R%.0f L%.0f B%.0f mm}", e ? std::hypot(e->x - x, e->y - y) : -1,
                          e0 ? std::hypot(e0->x - x, e0->y - y) : -1, eb ? std::hypot(eb->x - x, eb->y - y) : -1);
            }
          }
          if (f)
            std::printf("%c%.2f(%.0f,%.0f,%.0f)%.0f ", tag, f->score, f->rgb[0], f->rgb[1], f->rgb[2],
                        std::hypot(f->position.x - p.x, f->position.y - p.y));
          else
            std::printf("- ");
        }
        std::printf("\n");
        if (!ok) {
          const GridPx g = pipeline.grid().toGrid(onPlane(t.x(), t.y(), t.height()));
          const cv::Mat rgb = pipeline.debugRectified(), sc = pipeline.debugScore();
          const int half = 40;
          cv::Rect roi(static_cast<int>(g.x) - half, static_cast<int>(g.y) - half, 2 * half, 2 * half);
          roi &= cv::Rect(0, 0, rgb.cols, rgb.rows);
          cv::Mat a, b, bc, both;
          cv::resize(rgb(roi), a, {}, 6, 6, cv::INTER_NEAREST);
          cv::resize(sc(roi), b, {}, 6, 6, cv::INTER_NEAREST);
          cv::cvtColor(b, bc, cv::COLOR_GRAY2BGR);
          cv::hconcat(a, bc, both);
          char name[128];
          std::snprintf(name, sizeof name, "/tmp/side_probe/%d_%c%d.png", k, team == Team::Yellow ? 'Y' : 'B',
                        static_cast<int>(t.robot_id()));
          cv::imwrite(name, both);
        }
      }
    };
    run(frame.truth.robots_yellow(), Team::Yellow);
    run(frame.truth.robots_blue(), Team::Blue);
  }
  std::printf("missed %d of %d\n", missed, total);
}

}  // namespace
}  // namespace dv

// Temporary diagnosis of the side view's lost and misidentified robots.
// DV_SIDE_DIAG=1 to run.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "detection/color_classes.h"
#include "detection/seen_color.h"
#include "detection/pattern_fit.h"
#include "pipeline/view_stretch.h"
#include "scene_scoring.h"

namespace dv {
namespace {

TEST(SideViewDiagnosis, PrintFailures) {
  if (!std::getenv("DV_SIDE_DIAG")) GTEST_SKIP();
  const double radius = std::atof(std::getenv("DV_SIDE_DIAG"));
  for (int k = 0; k < 6; ++k) {
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
    popt.bayer = test::pipelineBayer(spec);
    CpuPipeline pipeline(cam, spec.field, popt);
    Detector detector(cam, spec.field, DetectorOptions{});
    BlobList blobs;
    Detections out;
    const RenderedFrame frame = renderer.render(0, 0);
    ASSERT_TRUE(pipeline.process(frame.image, blobs));
    detector.process(blobs, frame.truth.t_capture(), out, FrameView{&frame.image, popt.bayer});
    const Eigen::Vector3d cpos = cam.position();
    const RectifiedGrid& grid = pipeline.grid();
    const float* score = pipeline.scoreData();
    auto onPlane = [&](double x, double y, double z) {
      const double s = (cpos.z() - blobs.plane_height) / (cpos.z() - z);
      return FieldMm{cpos.x() + s * (x - cpos.x()), cpos.y() + s * (y - cpos.y())};
    };
    auto nearest = [&](const std::vector<Blob>& list, FieldMm p, double tol) -> const Blob* {
      const Blob* best = nullptr;
      for (const auto& b : list) {
        const double d = std::hypot(b.position.x - p.x, b.position.y - p.y);
        if (d < tol) tol = d, best = &b;
      }
      return best;
    };
    // Truth-based side colors of this frame: mean features of strong blobs at
    // green / pink slots.
    ColorVec mean[2];
    int cnt[2] = {0, 0};
    auto forSlots = [&](auto&& fn) {
      for (int team = 0; team < 2; ++team) {
        const auto& list = team == 0 ? frame.truth.robots_yellow() : frame.truth.robots_blue();
        for (const auto& t : list) fn(t, team);
      }
    };
    forSlots([&](const auto& t, int) {
      const auto colors = patternColors(static_cast<int>(t.robot_id()));
      const double cs = std::cos(t.orientation()), sn = std::sin(t.orientation());
      for (int i = 0; i < 4; ++i) {
        const FieldMm o = RobotPatternGeometry::kSideBlobs[i];
        const FieldMm p = onPlane(t.x() + cs * o.x - sn * o.y, t.y() + sn * o.x + cs * o.y, t.height());
        if (const Blob* b = nearest(blobs.blobs, p, 12)) {
          const int c = colors[i] == MarkerColor::Pink;
          const ColorVec f = colorFeature(b->rgb[0], b->rgb[1], b->rgb[2]);
          for (int q = 0; q < 3; ++q) mean[c].c[q] += f.c[q];
          ++cnt[c];
        }
      }
    });
    for (int c = 0; c < 2; ++c)
      for (int q = 0; q < 3; ++q) mean[c].c[q] /= std::max(1, cnt[c]);
    std::printf("placement %d: green (%.0f %.0f %.0f) n=%d pink (%.0f %.0f %.0f) n=%d\n", k, mean[0].c[0],
                mean[0].c[1], mean[0].c[2], cnt[0], mean[1].c[0], mean[1].c[1], mean[1].c[2], cnt[1]);
    const FrameView view{&frame.image, popt.bayer};
    forSlots([&](const auto& t, int team) {
      const auto colors = patternColors(static_cast<int>(t.robot_id()));
      const double cs = std::cos(t.orientation()), sn = std::sin(t.orientation());
      ColorVec f[4];
      double share[4];
      for (int i = 0; i < 4; ++i) {
        const FieldMm o = RobotPatternGeometry::kSideBlobs[i];
        const SeenColor c = seenDiscColor(view, cam, {t.x() + cs * o.x - sn * o.y, t.y() + sn * o.x + cs * o.y, t.height()}, radius);
        f[i] = colorFeature(c.rgb[0], c.rgb[1], c.rgb[2]);
        share[i] = c.share;
      }
      const double dist = std::hypot(t.x() - cpos.x(), t.y() - cpos.y());
      std::printf("  probe %s%d %.2f m:", team ? "B" : "Y", static_cast<int>(t.robot_id()), dist / 1000);
      for (int i = 0; i < 4; ++i) {
        ColorVec ref[2];
        int n[2] = {0, 0};
        for (int j = 0; j < 4; ++j) {
          if (j == i || share[j] < 0.99 || std::getenv("DV_FRAME_REF")) continue;
          const int c = colors[j] == MarkerColor::Pink;
          for (int q = 0; q < 3; ++q) ref[c].c[q] += f[j].c[q];
          ++n[c];
        }
        for (int c = 0; c < 2; ++c) {
          if (n[c]) for (int q = 0; q < 3; ++q) ref[c].c[q] /= n[c];
          else ref[c] = mean[c];
        }
        const double dg = colorDistance(f[i], ref[0]), dp = colorDistance(f[i], ref[1]);
        std::printf(" %s%s %.2f(%d%d %.1f)", colors[i] == MarkerColor::Pink ? "P" : "G",
                    (colors[i] == MarkerColor::Pink) == (dp < dg) ? "" : "!", dp < dg ? dp / dg : dg / dp, n[0], n[1], share[i]);
      }
      std::printf("\n");
    });
    forSlots([&](const auto& t, int team) {
      const int id = static_cast<int>(t.robot_id());
      const RobotDetection* det = nullptr;
      for (const auto& r : out.robots)
        if (std::hypot(r.position.x - t.x(), r.position.y - t.y()) < 60) det = &r;
      const bool ok = det && static_cast<int>(det->team) == team && det->id == id;
      if (ok) return;
      const double dist = std::hypot(t.x() - cpos.x(), t.y() - cpos.y());
      std::printf(" robot %s %d at (%.0f %.0f) %.2f m: ", team ? "B" : "Y", id, t.x(), t.y(), dist / 1000);
      {
        double d[2];
        std::printf("stretch %.2f ", viewStretch(cam, {t.x(), t.y()}, 140, d));
      }
      if (det)
        std::printf("detected %s %d conf %.2f\n", det->team == Team::Blue ? "B" : "Y", det->id, det->confidence);
      else
        std::printf("not detected\n");
      const auto colors = patternColors(id);
      const double cs = std::cos(t.orientation()), sn = std::sin(t.orientation());
      FieldMm slot_at[5];
      for (int s = 0; s < 5; ++s) {
        const FieldMm o = s == 0 ? FieldMm{0, 0} : RobotPatternGeometry::kSideBlobs[s - 1];
        slot_at[s] = onPlane(t.x() + cs * o.x - sn * o.y, t.y() + sn * o.x + cs * o.y, t.height());
      }
      for (int w = 0; w < 2; ++w)
        for (const auto& b : w ? blobs.weak : blobs.blobs) {
          if (std::hypot(b.position.x - slot_at[0].x, b.position.y - slot_at[0].y) > 110) continue;
          int best = 0;
          double bd = 1e9;
          for (int s = 0; s < 5; ++s) {
            const double d = std::hypot(b.position.x - slot_at[s].x, b.position.y - slot_at[s].y);
            if (d < bd) bd = d, best = s;
          }
          const double ox = b.position.x - slot_at[best].x, oy = b.position.y - slot_at[best].y;
          const double ux = slot_at[best].x - cpos.x(), uy = slot_at[best].y - cpos.y(), un = std::hypot(ux, uy);
          std::printf("   (%.0f %.0f)%s ", b.position.x, b.position.y, b.streak ? " STREAK" : "");
          std::printf("   %s %.3f near slot %d: %.1f mm (along ray %.1f, across %.1f) rgb (%.0f %.0f %.0f)\n",
                      w ? "weak" : "blob", b.score, best, bd, (ox * ux + oy * uy) / un, (-ox * uy + oy * ux) / un,
                      b.rgb[0], b.rgb[1], b.rgb[2]);
        }
      for (int s = 0; s < 5; ++s) {
        const FieldMm o = s == 0 ? FieldMm{0, 0} : RobotPatternGeometry::kSideBlobs[s - 1];
        const double fx = t.x() + cs * o.x - sn * o.y, fy = t.y() + sn * o.x + cs * o.y;
        const FieldMm p = onPlane(fx, fy, t.height());
        // Image size of the dot: extent along and across the viewing ray.
        const double r = s == 0 ? 25 : 20;
        const double ux = fx - cpos.x(), uy = fy - cpos.y(), un = std::hypot(ux, uy);
        auto px = [&](double a, double b) {
          return cam.fieldToImage({fx + a * ux / un - b * uy / un, fy + a * uy / un + b * ux / un, t.height()});
        };
        const auto c0 = px(0, 0), a0 = px(-r, 0), a1 = px(r, 0), b0 = px(0, -r), b1 = px(0, r);
        double along = 0, across = 0;
        if (a0 && a1) along = std::hypot(a1->u - a0->u, a1->v - a0->v);
        if (b0 && b1) across = std::hypot(b1->u - b0->u, b1->v - b0->v);
        const GridPx g = grid.toGrid(p);
        float best = -9;
        const int gx = static_cast<int>(std::lround(g.x)), gy = static_cast<int>(std::lround(g.y));
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            const int x = gx + dx, y = gy + dy;
            if (x >= 0 && y >= 0 && x < grid.width && y < grid.height)
              best = std::max(best, score[static_cast<size_t>(y) * grid.width + x]);
          }
        std::printf("   slot %d %s px (%.0f %.0f) dot %.1f x %.1f px, score max %.3f", s,
                    s == 0 ? "C" : (colors[s - 1] == MarkerColor::Green ? "G" : "P"), c0 ? c0->u : -1,
                    c0 ? c0->v : -1, along, across, best);
        auto show = [&](const char* what, const Blob* b) {
          if (!b) return;
          const ColorVec f = colorFeature(b->rgb[0], b->rgb[1], b->rgb[2]);
          std::printf(" | %s %.3f rgb (%.0f %.0f %.0f) f (%.0f %.0f %.0f) dG %.1f dP %.1f", what, b->score,
                      b->rgb[0], b->rgb[1], b->rgb[2], f.c[0], f.c[1], f.c[2], colorDistance(f, mean[0]),
                      colorDistance(f, mean[1]));
        };
        show("blob", nearest(blobs.blobs, p, 12));
        show("weak", nearest(blobs.weak, p, 12));
        std::printf("\n");
      }
    });
  }
}

}  // namespace
}  // namespace dv

// Robots of which only a side dot peaked (detector_impl.h,
// robotsAroundLoneSides).
#include <algorithm>
#include <cmath>

#include "detection/detector_impl.h"
#include "detection/ring_orientation.h"

namespace dv {

int Detector::Impl::robotsAroundLoneSides() {
  if (!frame_view.image || !opt.probe_missing_sides) return 0;
  const HypothesisInputs in = searchInputs(frame_color);
  constexpr int kSteps = 72;  // 5 degrees: 5.7 mm apart on the circle
  const double ring = RobotPatternGeometry::kSideBlobDistance;
  int added = 0;
  for (int a = 0; a < n_strong; ++a) {
    const FrameBlob& side = blobs[a];
    if (!side.valid || side.weak || side.streak || side.robot >= 0 || !sideColored(ClippedColor(side.rgb)))
      continue;
    // The center lies on the circle of the side distance around the dot:
    // where that circle is brightest (a washed center is as bright as a
    // marker; the rest of the circle crosses the dark top or the carpet).
    // Each step's brightness: the mean of nine points over the probe's disc
    // around the step's pixel (a lattice on the field would cost a
    // projection per point).
    const double width = frame_view.image->cols, height = frame_view.image->rows;
    const auto dot_px = camera.fieldToImage({side.at_ref.x, side.at_ref.y, ref_height});
    const auto rim_px = camera.fieldToImage({side.at_ref.x + opt.probe_radius, side.at_ref.y, ref_height});
    if (!dot_px || !rim_px) continue;
    const double r_px = std::hypot(rim_px->u - dot_px->u, rim_px->v - dot_px->v);
    float bright[kSteps];
    int best = -1;
    for (int i = 0; i < kSteps; ++i) {
      const double t = 2 * kPi * i / kSteps;
      const auto px =
          camera.fieldToImage({side.at_ref.x + ring * std::cos(t), side.at_ref.y + ring * std::sin(t), ref_height});
      bright[i] = 0;
      if (px && px->u >= r_px && px->v >= r_px && px->u < width - r_px && px->v < height - r_px) {
        for (int k = 0; k < 9; ++k) {
          const double phi = kPi / 4 * k, r = k == 8 ? 0 : r_px;
          float rgb[3];
          frameRgbAt(frame_view, px->u + r * std::cos(phi), px->v + r * std::sin(phi), rgb);
          bright[i] += (rgb[0] + rgb[1] + rgb[2]) / 9;
        }
      }
      if (best < 0 || bright[i] > bright[best]) best = i;
    }
    if (bright[best] < kMarkerBrightness * side.brightness()) continue;
    // Between the steps: the vertex of the parabola through the brightest
    // step and its two neighbours.
    const float l = bright[(best + kSteps - 1) % kSteps], m = bright[best], r = bright[(best + 1) % kSteps];
    const float curve = l - 2 * m + r;
    const double shift = curve < 0 ? std::clamp(0.5 * (l - r) / curve, -0.5, 0.5) : 0;
    const double t = 2 * kPi * (best + shift) / kSteps;
    const FieldMm at{side.at_ref.x + ring * std::cos(t), side.at_ref.y + ring * std::sin(t)};
    // A center that peaked is the searches' to judge.
    bool peaked = false;
    for (const auto& hit : index.within(at, RobotPatternGeometry::kCenterBlobRadius))
      peaked = peaked || blobs[hit.first].valid;
    if (peaked) continue;
    const SeenColor seen = seenDiscColor(frame_view, camera, {at.x, at.y, ref_height}, opt.probe_radius);
    Team team;
    if (seen.share < 1 || !teamColored(ClippedColor(seen.rgb), &team)) continue;
    // On a robot's dark top: a sun-lit carpet is bright all round, and its
    // texture's peaks fill a pattern (no-ball moderate #994).
    const auto top = ringDarkest(frame_view, camera, {at.x, at.y, ref_height});
    if (!top || seen.rgb[0] + seen.rgb[1] + seen.rgb[2] < kDotOverTop * *top) continue;
    // The blob list's reserve bounds it (no allocation per frame).
    const FrameBlob center = centerBlobAt(at, seen.rgb);
    if (!center.valid || blobs.size() == blobs.capacity()) continue;
    blobs.push_back(center);
    const int c = static_cast<int>(blobs.size()) - 1;
    Hypothesis h = search.bestAt(in, c);
    bool free = h.rank > 0 && !overlapsAccepted(h.pose);
    for (int i = 1; i < h.n && free; ++i) free = blobs[h.blob[i]].robot < 0;
    if (!free) {
      blobs.pop_back();
      continue;
    }
    h.team = team;
    h.confidence = h.rank;
    for (int i = 0; i < h.n; ++i) blobs[h.blob[i]].robot = static_cast<int>(robots.size());
    robots.push_back(h);
    ++added;
  }
  return added;
}

}  // namespace dv

#include "detection/detector_impl.h"
#include "detection/partial_ids.h"
#include "detection/seen_color.h"

namespace dv {

void Detector::Impl::orderByRatio(TwoMeansResult& r, int num, int den) {
  dv::orderByRatio(r, labels.data(), static_cast<int>(samples.size()), num, den,
                   neutral.valid ? neutral.rgb : nullptr);
}

// A center clipped in all three channels, which says nothing of its color,
// clusters by its unclipped samples where it has them (a center clipped
// in two is judged by the colors it may have been: its unclipped channel
// tells more than its rim, which mixes with the robot's dark top).
bool Detector::Impl::readByRim(const FrameBlob& b) {
  return b.has_unclipped && std::min({b.rgb[0], b.rgb[1], b.rgb[2]}) >= kClipLevel;
}

const float* Detector::Impl::centerRgb(const FrameBlob& b) { return readByRim(b) ? b.unclipped_rgb : b.rgb; }

void Detector::Impl::addSample(const float rgb[3]) {
  samples.push_back(colorFeature(rgb[0], rgb[1], rgb[2]));
  sample_rgb.push_back({rgb[0], rgb[1], rgb[2]});
}

TwoMeansResult Detector::Impl::splitSides(const ColorVec ext[2]) {
  samples.clear();
  sample_rgb.clear();
  for (const auto& r : robots)
    for (int i = 1; i < r.n; ++i)
      if (!blobs[r.blob[i]].weak) addSample(blobs[r.blob[i]].rgb);
  labels.resize(samples.size());
  const ColorVec prior[2] = {classes[kGreen].color, classes[kPink].color};
  auto res = twoMeans(samples.data(), static_cast<int>(samples.size()), prior, ext, 2, labels.data());
  orderByRatio(res, 0, 1);  // red over green: pink's far above green's
  return res;
}

TwoMeansResult Detector::Impl::clusterCenters(bool from_unclipped) {
  // The team split is weighed against the side colors this frame shows,
  // not the classes: in a first frame those are still the references,
  // and a washed-out frame's markers all lie far from them (lemon centers
  // at exposure 1.4 under tungsten, saturation 0.4: the split from navy
  // failed eq. 5.24 by 0.1 against the reference green and pink, and every
  // yellow robot was dropped as a line-colored center).
  const ColorVec teams[2] = {classes[kYellow].color, classes[kBlue].color};
  const TwoMeansResult sides = splitSides(teams);
  const ColorVec ext[2] = {sides.count[0] > 0 ? sides.mean[0] : classes[kGreen].color,
                           sides.count[1] > 0 ? sides.mean[1] : classes[kPink].color};
  auto learnsSplit = [&](const Hypothesis& r, bool any_free) {
    return !from_unclipped || !any_free || !centerSeen(blobs[r.blob[0]]).saturated();
  };
  bool any_free = false;
  for (const auto& r : robots) any_free = any_free || learnsSplit(r, true);
  samples.clear();
  sample_rgb.clear();
  for (const auto& r : robots)
    if (learnsSplit(r, any_free)) addSample(centerRgb(blobs[r.blob[0]]));
  labels.resize(samples.size());
  const int n = static_cast<int>(samples.size());
  TwoMeansResult res = twoMeans(samples.data(), n, teams, ext, 2, labels.data());
  orderByRatio(res, 2, 1);  // blue over green: blue's far above yellow's
  auto labelCenters = [&] {
    center_labels.clear();
    size_t j = 0;
    for (const auto& r : robots) {
      const ClippedColor c = centerSeen(blobs[r.blob[0]]);
      center_labels.push_back(learnsSplit(r, any_free) ? labels[j++]
                              : c.distance(res.mean[0]) <= c.distance(res.mean[1]) ? 0 : 1);
    }
  };
  labelCenters();
  if (res.separated && splitByClipping(res)) {
    res = oneClass(samples.data(), n, teams, -1, labels.data());
    orderByRatio(res, 2, 1);
    labelCenters();
  }
  return res;
}

bool Detector::Impl::splitByClipping(const TwoMeansResult& r) const {
  for (int k = 0; k < 2; ++k) {
    const float reach = classReach(clusterSpread(r, 1 - k));
    bool explained = true;
    int clipped = 0, unclipped = 0;
    for (size_t i = 0; i < robots.size() && explained; ++i) {
      if (center_labels[i] != k) continue;
      const ClippedColor c = centerSeen(blobs[robots[i].blob[0]]);
      ++(c.clipped() ? clipped : unclipped);
      explained = !c.clipped() || c.distance(r.mean[1 - k]) <= reach;
    }
    if (explained && clipped > unclipped) return true;
  }
  return false;
}

ClippedColor Detector::Impl::centerSeen(const FrameBlob& b) { return ClippedColor(centerRgb(b)); }

template <class Drop>
int Detector::Impl::dropRobots(Drop drop, bool implausible) {
  const int nr = static_cast<int>(robots.size());
  int kept = 0;
  for (int i = 0; i < nr; ++i) {
    const bool dropped = drop(i);
    for (int b = 0; b < robots[i].n; ++b) blobs[robots[i].blob[b]].robot = dropped ? -1 : kept;
    if (dropped) {
      blobs[robots[i].blob[0]].implausible_center = blobs[robots[i].blob[0]].implausible_center || implausible;
      continue;
    }
    robots[kept++] = robots[i];
  }
  robots.resize(kept);
  return nr - kept;
}

int Detector::Impl::dropImplausibleCenters() {
  if (robots.empty()) return 0;
  const auto res = clusterCenters();
  return dropRobots(
      [&](int i) {
        // A center clipped in two channels (a yellow top in a sun patch) is
        // judged by the colors it may have been, as the field and the lines
        // are; one clipped in all three by its rim where it has one
        // (centerRgb: a line crossing's is line and carpet), else as seen.
        const FrameBlob& center = blobs[robots[i].blob[0]];
        const ClippedColor c = centerSeen(center);
        const float d_team = c.distance(res.mean[center_labels[i]]);
        const float d_bg = std::min(c.distance(classes[kField].color), c.distance(classes[kWhite].color));
        // One with no hue left (clipped white in a sun patch) is its four
        // side blobs' center, where no markings cross (their false colors
        // make patterns): its rim, the robot's dark top mixed with the
        // light, reads as gray as a line's.
        const bool by_pattern =
            ClippedColor(center.rgb).white() && robots[i].n == kPatternSlots && !atCrossing(center.at_ball);
        return !by_pattern && d_bg < d_team;
      },
      true);
}

void Detector::Impl::dropCentersAloneAtCrossings() {
  // (Tungsten, lemon centers and yellow-green dots at 1224 x 1024: where
  // the center circle crosses the halfway line, the thin lines' false
  // colors read as a lemon center and its arms as four yellow-green dots.)
  dropRobots([&](int i) { return robots[i].n == 1 && atCrossing(blobs[robots[i].blob[0]].at_ball); }, false);
}

void Detector::Impl::dropSecondIds() {
  const size_t n = robots.size();
  second_id.assign(n, 0);
  auto surer = [&](const Hypothesis& a, const Hypothesis& b) {
    return a.id_known != b.id_known ? a.id_known : a.confidence > b.confidence;
  };
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      if (robots[i].team == robots[j].team && robots[i].id == robots[j].id)
        second_id[surer(robots[j], robots[i]) ? i : j] = 1;
  dropRobots([&](int i) { return second_id[i] != 0; }, false);
}

void Detector::Impl::dropDotsTakenForCenters() {
  dropRobots(
      [&](int i) {
        const Hypothesis& r = robots[i];
        if (r.n > 2) return false;
        const ClippedColor c = centerSeen(blobs[r.blob[0]]);
        const float d_team = c.distance(frame_color[r.team == Team::Yellow ? kYellow : kBlue]);
        bool dot = false;
        for (int k : {kGreen, kPink}) dot = dot || (frame_seen[k] && c.distance(frame_color[k]) < d_team);
        return dot;
      },
      true);
}

void Detector::Impl::learnClass(int a, int b, const TwoMeansResult& r) {
  learnClassFrom(a, r, 0);
  learnClassFrom(b, r, 1);
}

float Detector::Impl::clusterSpread(const TwoMeansResult& r, int label) const {
  double sum = 0;
  for (size_t i = 0; i < samples.size() && i < labels.size(); ++i)
    if (labels[i] == label) {
      const float d = ClippedColor(sample_rgb[i].data()).distance(r.mean[label]);
      sum += d * d;
    }
  return r.count[label] > 1 ? static_cast<float>(std::sqrt(sum / r.count[label])) : 0.f;
}

void Detector::Impl::learnClassFrom(int cls, const TwoMeansResult& r, int label) {
  frame_spread[cls] = clusterSpread(r, label);
  if (r.count[label] == 0) return;
  frame_seen[cls] = true;
  frame_color[cls] = r.mean[label];
  classes[cls].update(r.mean[label], static_cast<float>(opt.retention_force), static_cast<float>(opt.reference_force));
}

void Detector::Impl::learnFrameColors() {
  for (int k = 0; k < kNumClasses; ++k)
    frame_color[k] = classes[k].color, frame_seen[k] = false, frame_spread[k] = 0;
  const int nr = static_cast<int>(robots.size());
  if (nr == 0) return;

  // Teams: center blobs, yellow vs blue; green and pink are external.
  {
    const auto res = clusterCenters();
    health.center_blobs = nr;
    health.teams_separated = res.separated;
    for (int i = 0; i < nr; ++i) robots[i].team = center_labels[i] == 0 ? Team::Yellow : Team::Blue;
    learnClass(kYellow, kBlue, res);
    float sum[2] = {0, 0};
    int count[2] = {0, 0};
    for (int i = 0; i < nr; ++i) sum[center_labels[i]] += blobs[robots[i].blob[0]].brightness(), ++count[center_labels[i]];
    for (int k = 0; k < 2; ++k) team_brightness[k] = count[k] > 0 ? sum[k] / count[k] : 0.f;
    // The reddest yellow center under the lines' white: a color redder
    // than every one of them is no yellow the frame shows (explainedByNone).
    // A center clipped in a channel shows a color it does not have (a
    // lemon yellow clipped in green reads as orange as a light orange
    // ball): only unclipped ones count.
    yellow_hue_min = std::numeric_limits<float>::max();
    if (neutral.valid)
      for (int i = 0; i < nr; ++i) {
        const FrameBlob& c = blobs[robots[i].blob[0]];
        if (center_labels[i] == 0 && !ClippedColor(c.rgb).clipped())
          yellow_hue_min = std::min(yellow_hue_min, colorHue(c.rgb, neutral.rgb));
      }
  }

  // Side blobs of all robots: green vs pink; the team colors are external.
  {
    const ColorVec teams[2] = {frame_color[kYellow], frame_color[kBlue]};
    const TwoMeansResult res = splitSides(teams);
    health.side_blobs = static_cast<int>(samples.size());
    health.sides_separated = res.separated;
    // This frame's side colors seed the per-robot clustering.
    const ColorVec green = res.count[0] > 0 ? res.mean[0] : classes[kGreen].color;
    const ColorVec pink = res.count[1] > 0 ? res.mean[1] : classes[kPink].color;
    learnClass(kGreen, kPink, res);
    frame_color[kGreen] = green;
    frame_color[kPink] = pink;
    if (res.count[1] == 0) pinkFromUnseenSlots();
  }
}

void Detector::Impl::identifyRobots() {
  if (robots.empty()) return;
  IdentityContext context{&blobs, frame_color[kGreen], frame_color[kPink], frame_view, &camera, &opt};
  context.green_spread = frame_spread[kGreen], context.pink_spread = frame_spread[kPink];
  context.sides_separated = health.sides_separated;
  if (neutral.valid) context.white = &classes[kWhite].color;
  for (auto& r : robots) identifyRobot(r, context);
  resolvePartialIds(robots);

  // How this camera shows the pattern colors tells where its orange is.
  ColorVec ref[4], seen[4];
  int n = 0;
  for (int k : {kYellow, kBlue, kGreen, kPink})
    if (frame_seen[k]) ref[n] = classes[k].reference, seen[n] = frame_color[k], ++n;
  color_map.fit(ref, seen, n);
}

void Detector::Impl::pinkFromUnseenSlots() {
  if (!opt.probe_missing_sides || !frame_view.image) return;
  const size_t n_blobs = samples.size();
  for (const auto& r : robots) {
    unsigned filled = 0;
    for (int i = 1; i < r.n; ++i) filled |= 1u << r.slot[i];
    if (filled == 0x1Eu) continue;
    Hypothesis at_team = r;
    refit(at_team);
    for (int s = 1; s < kPatternSlots; ++s) {
      if (filled >> s & 1u) continue;
      const FieldMm p = slotPosition(at_team.pose.position, at_team.pose.orientation, s);
      const SeenColor seen = seenDiscColor(frame_view, camera, {p.x, p.y, teamHeight(r.team)}, opt.probe_radius);
      // In view, and no darker than a marker may be (not the robot top).
      if (seen.share < opt.min_probe_share ||
          seen.rgb[0] + seen.rgb[1] + seen.rgb[2] < kMarkerBrightness * blobs[r.blob[0]].brightness())
        continue;
      addSample(seen.rgb);
    }
  }
  if (samples.size() == n_blobs) return;
  labels.resize(samples.size());
  const ColorVec prior[2] = {frame_color[kGreen], classes[kPink].color};
  const ColorVec ext[2] = {frame_color[kYellow], frame_color[kBlue]};
  TwoMeansResult res = twoMeans(samples.data(), static_cast<int>(samples.size()), prior, ext, 2, labels.data());
  orderByRatio(res, 0, 1);
  // Two shades of green split as well: the pink must be redder than white.
  auto redOverGreen = [](const float* c) { return c[0] / std::max(c[1], 1e-3f); };
  if (!res.separated || res.count[1] == 0 || !neutral.valid ||
      redOverGreen(res.mean[1].c) <= redOverGreen(neutral.rgb))
    return;
  frame_color[kPink] = res.mean[1];
}

void Detector::Impl::refit(Hypothesis& h) const { refitAtTeamHeight(h, blobs, opt.score_scale); }

}  // namespace dv

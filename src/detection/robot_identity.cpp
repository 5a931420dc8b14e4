#include "detection/robot_identity.h"

#include <algorithm>
#include <cmath>

#include "detection/clipped_color.h"
#include "detection/weak_sides.h"

namespace dv {
namespace {

// Whether `dot` lies on pink's side of the lines' `white` along the line
// from green to pink. A dot lit toward white stays on its own side: a green
// dot at a sun patch's edge, (94, 106, 93) against the others' (83, 127,
// 82), was redder than they and split from them as pink, yet it lay on
// green's side of the white, (94, 102, 98). Only for the one dot read
// beside three seen sides: the lines are no neutral where they clip, and
// under tungsten at saturation 0.4 and gamma 0.6 (lines (232, 242, 213))
// every read dot lay on pink's side; applied to all, 29 of 69 robots in
// H.264 at 3 Mbit/s became all pink. Nor for a dot clipped in two
// channels or more: its hue is gone or rests on one channel (a pink one at
// (242, 247, 241) lay on green's side of a white of (218, 226, 226); under
// a magenta cast, whose lines are low in green, so did pinks clipped in
// red and blue in a sun patch of 2.5).
bool pinkSideOfWhite(const ColorVec& dot, const ColorVec& white, const ColorVec& green, const ColorVec& pink) {
  float along = 0;
  for (int k = 0; k < 3; ++k) along += (dot.c[k] - white.c[k]) * (pink.c[k] - green.c[k]);
  return along > 0;
}

// A lone slot read clipped beside three seen sides of one color: that
// color is there only if the light there could clip it. Over a robot's top
// the light is smooth, so the three dots give its plane: read in a channel
// the slot clipped and none of the three did, the seen color is predicted
// there by that plane (plus the change seen among the three, for a light
// that bends). Where that stays below the clip level, the slot holds the
// other color. (A sun patch under a magenta cast: greens read (165, 255,
// 203) alike on three slots, the fourth a rose dot clipped to (254, 250,
// 253); guessed green, blue 12 was reported as 8. At a sun patch's soft
// edge the seen greens differ, (119, 210, 75) and (217, 255, 137), and a
// third lit more clips toward white: a green fits, the slot stays a
// guess.) Returns the unseen slot, or -1.
int slotClippedBeyondItsNeighbours(const Hypothesis& r, const FieldMm at[4], const float rgb[4][3],
                                   const bool read[4], const bool clipped[4],
                                   const std::array<MarkerColor, 4>& colors) {
  int lone = -1, seen[3], n = 0;
  for (int s = 0; s < 4; ++s)
    if (!(r.seen_sides >> s & 1)) lone = s;
    else if (read[s]) seen[n++] = s;
  if (lone < 0 || n != 3 || !read[lone] || !clipped[lone]) return -1;
  if (colors[seen[0]] != colors[seen[1]] || colors[seen[0]] != colors[seen[2]]) return -1;
  // The slot as an affine combination of the three (the weights a plane's
  // values there are made of).
  const double ax = at[seen[1]].x - at[seen[0]].x, ay = at[seen[1]].y - at[seen[0]].y;
  const double bx = at[seen[2]].x - at[seen[0]].x, by = at[seen[2]].y - at[seen[0]].y;
  const double px = at[lone].x - at[seen[0]].x, py = at[lone].y - at[seen[0]].y;
  const double det = ax * by - ay * bx;
  if (std::abs(det) < 1e-6) return -1;
  const double u = (px * by - py * bx) / det, v = (ax * py - ay * px) / det;
  for (int k = 0; k < 3; ++k) {
    if (rgb[lone][k] < kClipLevel) continue;
    const float l0 = rgb[seen[0]][k], l1 = rgb[seen[1]][k], l2 = rgb[seen[2]][k];
    if (std::max({l0, l1, l2}) >= kClipLevel) continue;
    const double predicted = (1 - u - v) * l0 + u * l1 + v * l2;
    if (predicted + (std::max({l0, l1, l2}) - std::min({l0, l1, l2})) < kClipLevel) return lone;
  }
  return -1;
}

// Whether dot `x` and a seen dot `d` may be one marker color under two
// lights, within `radius` in chromaticity: the nearest color `d` may have
// (a clipped channel free to grow, ClippedColor) to `x` where `x` clipped
// nowhere, and, where just two channels are clipped in neither dot, their
// shares of those two (a light scales both alike; the third, clipped in
// one of them, says only "more").
bool mayBeOneColor(const float x[3], const float d[3], float radius) {
  const ClippedColor cx(x);
  if (!cx.clipped() && ClippedColor(d).distance(colorFeature(x[0], x[1], x[2])) > radius) return false;
  int u[3], n = 0;
  for (int k = 0; k < 3; ++k)
    if (x[k] < kClipLevel && d[k] < kClipLevel) u[n++] = k;
  if (n != 2) return true;
  // The two-channel chromaticity on colorFeature's scale (300 over the sum).
  auto share = [&](const float* c) { return 300.f * c[u[0]] / (c[u[0]] + c[u[1]] + 10.f); };
  return std::abs(share(x) - share(d)) * std::sqrt(2.f) <= radius;
}

// An unseen slot's dot that can be none of the colors its robot's seen
// dots show: where every seen side dot has one color, a dot clipped in one
// channel at most, bright as a marker (kMarkerBrightness of the center)
// and no nearer to any of them than a split of one color's noise (twice a
// class's least reach, color_classes.cpp; mayBeOneColor) is the other
// color. (Desaturated cold light: greens read (167, 240, 164) and (177,
// 246, 169), a pink dot beside them (234, 236, 224); too pale to split
// from them against the blue center by eq. 5.24, it was guessed green and
// blue 11 was reported as 8. Blue 2 beside greens (158, 247, 235): its
// lone pink, (238, 247, 239), clipped in green as they are, shows red to
// blue 1.00 against their 0.67; guessed green, it was reported as 8.)
bool noColorOfTheSeenDots(const float x_rgb[3], uint8_t seen, const float rgb[4][3], const bool read[4],
                          const std::array<MarkerColor, 4>& colors, float center_brightness) {
  if (ClippedColor(x_rgb).saturated() || x_rgb[0] + x_rgb[1] + x_rgb[2] < kMarkerBrightness * center_brightness)
    return false;
  int n = 0;
  MarkerColor first = MarkerColor::Green;
  for (int s = 0; s < 4; ++s) {
    if (!(seen >> s & 1)) continue;
    if (!read[s] || (n > 0 && colors[s] != first)) return false;
    first = colors[s];
    ++n;
    if (mayBeOneColor(x_rgb, rgb[s], 2 * kMinClassRadius)) return false;
  }
  return n > 0;
}

// The side slots of `r` that neither a blob nor a weak peak filled: the
// color the camera saw there (seen_color.h), when clearly nearer to the
// robot's own `green` or `pink`, sets the slot's marker. A dot read clipped
// in two channels or more only guesses it: its hue is gone, and at a sun
// patch's soft edge a green dot lit half as much again as its neighbours
// clips toward white like a pink (a blue 6 read as 11 and dropped beside
// the real 11). Left unseen, the slot is settled by the light its three
// neighbours show (slotClippedBeyondItsNeighbours) or by the ids fully
// seen teammates hold (partial_ids.h).
void probeMissingSides(Hypothesis& r, const IdentityContext& c, const ColorVec& green, const ColorVec& pink,
                       std::array<MarkerColor, 4>& colors) {
  const std::vector<FrameBlob>& blobs = *c.blobs;
  if (!c.opt->probe_missing_sides || !c.frame.image) return;
  const bool lone = __builtin_popcount(r.seen_sides) == 3;
  Hypothesis at_team = r;
  refitAtTeamHeight(at_team, blobs, c.opt->score_scale);
  const double z = r.team == Team::Yellow ? c.opt->robot_height_yellow : c.opt->robot_height_blue;
  // Each slot read once, its blob's too: the four dots compared under the
  // light they share, by the same reading.
  ColorVec dot[4];
  float dot_rgb[4][3];
  bool read[4] = {false, false, false, false};
  bool clipped[4] = {false, false, false, false};  // in two channels or more
  FieldMm at[4];
  int n_read = 0;
  for (int s = 1; s < kPatternSlots; ++s) {
    const FieldMm p = slotPosition(at_team.pose.position, at_team.pose.orientation, s);
    at[s - 1] = p;
    const SeenColor seen = seenDiscColor(c.frame, *c.camera, {p.x, p.y, z}, c.opt->probe_radius);
    if (seen.share < c.opt->min_probe_share) continue;
    dot[s - 1] = colorFeature(seen.rgb[0], seen.rgb[1], seen.rgb[2]);
    std::copy(seen.rgb, seen.rgb + 3, dot_rgb[s - 1]);
    clipped[s - 1] = ClippedColor(seen.rgb).saturated();
    read[s - 1] = true;
    ++n_read;
  }
  if (lone) {
    const int s = slotClippedBeyondItsNeighbours(r, at, dot_rgb, read, clipped, colors);
    if (s >= 0) {
      const int o = (s + 1) % 4;  // a seen side: the three share one color
      colors[s] = colors[o] == MarkerColor::Green ? MarkerColor::Pink : MarkerColor::Green;
      r.seen_sides |= static_cast<uint8_t>(1u << s);
      return;
    }
  }
  if (n_read == 4) {
    // All four dots in view: where they are of two colors they split by
    // themselves (the redder is pink, whatever the cast; a pale pink that
    // clipped toward white lies clearly nearer to neither frame class),
    // taken where the sides seen as blobs keep their colors and a single
    // dot read beside them lies on its label's side of the white.
    const ColorVec prior[2] = {green, pink};
    const ColorVec ext[1] = {blobs[r.blob[0]].color};
    uint8_t lab[4];
    TwoMeansResult res = twoMeans(dot, 4, prior, ext, 1, lab);
    dv::orderByRatio(res, lab, 4, 0, 1, nullptr);
    bool agrees = res.separated;
    for (int s = 0; s < 4 && agrees; ++s)
      if (r.seen_sides >> s & 1) agrees = colors[s] == (lab[s] == 0 ? MarkerColor::Green : MarkerColor::Pink);
      else if (c.white && !clipped[s] && __builtin_popcount(r.seen_sides) == 3)
        agrees = pinkSideOfWhite(dot[s], *c.white, green, pink) == (lab[s] == 1);
    if (agrees) {
      for (int s = 0; s < 4; ++s) {
        colors[s] = lab[s] == 0 ? MarkerColor::Green : MarkerColor::Pink;
        if (!(clipped[s] && lone)) r.seen_sides |= static_cast<uint8_t>(1u << s);
      }
      return;
    }
  }
  const uint8_t seen = r.seen_sides;
  const std::array<MarkerColor, 4> seen_colors = colors;
  for (int s = 0; s < 4; ++s) {
    if (!read[s] || (seen >> s & 1)) continue;
    int label =
        sideColorOfDot(dot[s], dot_rgb[s], green, pink, static_cast<float>(c.opt->weak_color_margin), colors[s]);
    if (label < 0 &&
        noColorOfTheSeenDots(dot_rgb[s], seen, dot_rgb, read, seen_colors, blobs[r.blob[0]].brightness())) {
      const int o = __builtin_ctz(seen);
      colors[s] = seen_colors[o] == MarkerColor::Green ? MarkerColor::Pink : MarkerColor::Green;
      label = 0;
    }
    if (label < 0 || (clipped[s] && lone)) continue;
    r.seen_sides |= static_cast<uint8_t>(1u << s);
  }
}

// Nor are two colors on one robot where both are nearer to one frame class
// and within its reach: that is one marker color split by its noise.
// (H.265 at 3 Mbit/s under a green cast: of a robot's three green dots one
// read bluish, 10 from the frame's green, whose reach was 24..33; split
// from the other two it was taken for pink, and the robot's real pink, a
// weak peak, for green.) Within reach alone is not enough: under uneven
// light a class's reach grows, and pale greens and pinks under tungsten
// both lay within the pink class's.
void oneClassIfWithinItsReach(TwoMeansResult& res, uint8_t* lab, int m, const ColorVec* samples,
                              const IdentityContext& c) {
  const ColorVec cls[2] = {c.green, c.pink};
  const float reach[2] = {classReach(c.green_spread), classReach(c.pink_spread)};
  auto nearer = [&](const ColorVec& x) { return colorDistance(x, cls[0]) <= colorDistance(x, cls[1]) ? 0 : 1; };
  const int k = nearer(res.mean[0]);
  if (nearer(res.mean[1]) == k && colorDistance(res.mean[0], cls[k]) <= reach[k] &&
      colorDistance(res.mean[1], cls[k]) <= reach[k])
    res = oneClass(samples, m, cls, k, lab);
}

// A robot's own dots held to eq. 5.24 against its center may make one
// cluster where the center's color lies far out: under a cold cast at
// gamma 0.61 an amber center read 134 from dots of (198, 141, 231) and
// (84, 178, 169), 65 apart, and seven of eight yellow robots read all pink.
// Where the frame's side blobs split, its two classes vouch instead: each
// dot clearly nearer to one of them (weak_color_margin), both present, and
// the redder still the pink.
void splitByFrameClasses(TwoMeansResult& res, uint8_t* lab, int m, const ColorVec* samples,
                         const IdentityContext& c) {
  if (!c.sides_separated || m < 2) return;
  TwoMeansResult split;
  uint8_t by_frame[4];
  for (int i = 0; i < m; ++i) {
    const int k = weakSideColor(samples[i], c.green, c.pink, static_cast<float>(c.opt->weak_color_margin));
    if (k < 0) return;
    by_frame[i] = static_cast<uint8_t>(k);
    ++split.count[k];
    for (int j = 0; j < 3; ++j) split.mean[k].c[j] += samples[i].c[j];
  }
  if (split.count[0] == 0 || split.count[1] == 0) return;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j) split.mean[k].c[j] /= split.count[k];
  auto redness = [](const ColorVec& v) { return v.c[0] / std::max(v.c[1], 1e-3f); };
  if (redness(split.mean[1]) < redness(split.mean[0])) return;
  split.separated = true;
  res = split;
  std::copy(by_frame, by_frame + m, lab);
}

}  // namespace

void identifyRobot(Hypothesis& r, const IdentityContext& c) {
  const std::vector<FrameBlob>& blobs = *c.blobs;
  ColorVec local[4];
  uint8_t lab[4];
  int side_of[4];
  int m = 0;
  for (int i = 1; i < r.n; ++i)
    if (!blobs[r.blob[i]].weak) side_of[m] = i, local[m++] = blobs[r.blob[i]].color;
  const ColorVec prior[2] = {c.green, c.pink};
  const ColorVec ext[1] = {blobs[r.blob[0]].color};
  TwoMeansResult res = twoMeans(local, m, prior, ext, 1, lab);
  // Two colors on one robot: the redder is pink, whatever the cast (a
  // pale pink under a magenta cast may lie nearer the frame's green).
  dv::orderByRatio(res, lab, m, 0, 1, nullptr);
  if (res.separated) oneClassIfWithinItsReach(res, lab, m, local, c);
  else splitByFrameClasses(res, lab, m, local, c);
  std::array<MarkerColor, 4> colors;
  colors.fill(MarkerColor::Green);  // a side nothing shows is guessed green
  r.seen_sides = 0;
  for (int i = 0; i < m; ++i) {
    const int slot = r.slot[side_of[i]];
    colors[slot - 1] = lab[i] == 0 ? MarkerColor::Green : MarkerColor::Pink;
    r.seen_sides |= static_cast<uint8_t>(1u << (slot - 1));
  }
  const ColorVec green = res.count[0] > 0 ? res.mean[0] : c.green;
  const ColorVec pink = res.count[1] > 0 ? res.mean[1] : c.pink;
  for (int i = 1; i < r.n; ++i) {
    if (!blobs[r.blob[i]].weak) continue;
    const FrameBlob& b = blobs[r.blob[i]];
    const int label = sideColorOfDot(b.color, b.rgb, green, pink, static_cast<float>(c.opt->weak_color_margin),
                                     colors[r.slot[i] - 1]);
    if (label < 0) continue;
    r.seen_sides |= static_cast<uint8_t>(1u << (r.slot[i] - 1));
  }
  if (r.seen_sides != 0xF) probeMissingSides(r, c, green, pink, colors);
  r.colors = colors;
  r.id = patternId(colors);
}

void refitAtTeamHeight(Hypothesis& h, const std::vector<FrameBlob>& blobs, double score_scale) {
  if (h.n == 1) {  // a center alone: along its ray, the orientation read from the frame
    h.pose.position = blobs[h.blob[0]].at_team[h.team == Team::Yellow ? 0 : 1];
    return;
  }
  int n_weak = 0;
  for (int i = 0; i < h.n; ++i) n_weak += blobs[h.blob[i]].weak;
  FieldMm pts[kPatternSlots];
  int slots[kPatternSlots];
  const int t = h.team == Team::Yellow ? 0 : 1;
  const bool blobs_only = n_weak > 0 && h.n - n_weak >= kPatternSlots - 1;
  int n = 0;
  for (int i = 0; i < h.n; ++i) {
    if (blobs_only && blobs[h.blob[i]].weak) continue;
    pts[n] = blobs[h.blob[i]].at_team[t];
    slots[n++] = h.slot[i];
  }
  h.pose = fitPattern(pts, slots, n, score_scale);
}

}  // namespace dv

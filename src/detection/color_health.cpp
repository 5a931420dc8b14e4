#include "detection/color_health.h"

#include <cmath>
#include <cstdio>

namespace dv {
namespace {
constexpr float kClippedLevel = 250;  // 8-bit level at which a line channel counts as clipped
}  // namespace

const char* ColorHealthWatch::name(ColorIssue i) {
  switch (i) {
    case ColorIssue::YellowMissing: return "yellow team missing";
    case ColorIssue::BlueMissing: return "blue team missing";
    case ColorIssue::BallMissing: return "ball missing";
    case ColorIssue::SidesInseparable: return "green and pink not separable";
  }
  return "?";
}

unsigned ColorHealthWatch::update(const DetectionHealth& h) {
  ++frames_;
  const bool evidence[kColorIssueCount] = {
      h.yellow == 0 && h.blue >= opt_.min_other_team,
      h.blue == 0 && h.yellow >= opt_.min_other_team,
      h.balls == 0 && h.yellow + h.blue >= opt_.min_robots_for_ball,
      h.side_blobs >= opt_.min_side_blobs && !h.sides_separated,
  };
  unsigned changed = 0;
  for (int i = 0; i < kColorIssueCount; ++i) {
    State& s = state_[i];
    s.evidence_total += evidence[i];
    s.run = evidence[i] != s.active ? s.run + 1 : 0;
    const int needed = i == static_cast<int>(ColorIssue::BallMissing) ? opt_.ball_frames_to_change
                                                                      : opt_.frames_to_change;
    if (s.run >= needed) {
      s.active = !s.active;
      s.run = 0;
      changed |= 1u << i;
    }
  }
  if (changed) last_ = h;

  cast_changed_ = false;
  if (h.lines.valid) {
    float gain[3];
    for (int k = 0; k < 3; ++k) gain[k] = h.lines.rgb[1] / h.lines.rgb[k];
    bool moved = !cast_said_;
    for (int k = 0; k < 3; ++k) moved = moved || std::abs(gain[k] / cast_gain_[k] - 1) > opt_.cast_change;
    if (moved) {
      cast_said_ = cast_changed_ = true;
      for (int k = 0; k < 3; ++k) cast_gain_[k] = gain[k], cast_rgb_[k] = h.lines.rgb[k];
    }
  }
  return changed;
}

std::string ColorHealthWatch::describe(ColorIssue i) const {
  const State& s = state_[static_cast<int>(i)];
  const int frames = i == ColorIssue::BallMissing ? opt_.ball_frames_to_change : opt_.frames_to_change;
  char buf[256];
  if (!s.active) {
    std::snprintf(buf, sizeof buf, "%s: over again (%d frames without its evidence)", name(i), frames);
    return buf;
  }
  switch (i) {
    case ColorIssue::YellowMissing:
    case ColorIssue::BlueMissing: {
      const bool yellow = i == ColorIssue::YellowMissing;
      std::snprintf(buf, sizeof buf,
                    "%s: no %s robot for %d frames while %d %s robots are seen (%d robot centers, "
                    "%s, yellow-blue class distance %.1f); check the camera's white balance and saturation",
                    name(i), yellow ? "yellow" : "blue", frames, yellow ? last_.blue : last_.yellow,
                    yellow ? "blue" : "yellow", last_.center_blobs,
                    last_.teams_separated ? "two clusters" : "one cluster", last_.yellow_blue);
      break;
    }
    case ColorIssue::BallMissing:
      std::snprintf(buf, sizeof buf, "%s: no ball for %d frames while %d robots are seen", name(i), frames,
                    last_.yellow + last_.blue);
      break;
    case ColorIssue::SidesInseparable:
      std::snprintf(buf, sizeof buf,
                    "%s: the %d side blobs of the robots form one cluster for %d frames (green-pink "
                    "class distance %.1f): ids are guesses",
                    name(i), last_.side_blobs, frames, last_.green_pink);
      break;
  }
  return buf;
}

std::string ColorHealthWatch::describeCast() const {
  char buf[256];
  int n = std::snprintf(buf, sizeof buf,
                        "the white lines read R %.0f G %.0f B %.0f: white balance gains that make them gray "
                        "R x%.2f G x%.2f B x%.2f",
                        cast_rgb_[0], cast_rgb_[1], cast_rgb_[2], cast_gain_[0], cast_gain_[1], cast_gain_[2]);
  // A clipped channel reads low: its gain is a bound, not a measurement.
  static const char* kChannel = "RGB";
  for (int k = 0; k < 3 && n > 0 && n < static_cast<int>(sizeof buf); ++k)
    if (cast_rgb_[k] >= kClippedLevel)
      n += std::snprintf(buf + n, sizeof buf - n, " (%c clipped: lower the exposure or that gain)", kChannel[k]);
  return buf;
}

std::string ColorHealthWatch::summary() const {
  std::string out;
  for (int i = 0; i < kColorIssueCount; ++i) {
    if (state_[i].evidence_total == 0) continue;
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s%s in %ld of %ld frames", out.empty() ? "" : ", ",
                  name(static_cast<ColorIssue>(i)), state_[i].evidence_total, frames_);
    out += buf;
  }
  return out;
}

}  // namespace dv

#pragma once
// Never silent: a color class that goes missing or collapses is said, with
// its evidence, once per change of state (detector.h's per-frame
// DetectionHealth in, state changes out), and counted for the summary.
//   - a team missing: no robot of one team while the other shows several;
//   - the ball missing: no ball for many frames while robots are seen;
//   - green and pink not separable: the side blobs form one cluster;
//   - the camera's cast: the white lines' color, at the start and whenever
//     it moves (what the camera's white balance should remove).
// A state starts after `frames_to_change` frames of agreeing evidence and
// ends after as many without, so one odd frame neither warns nor clears.
#include <string>

#include "detection/detector.h"

namespace dv {

enum class ColorIssue { YellowMissing, BlueMissing, BallMissing, SidesInseparable };
inline constexpr int kColorIssueCount = 4;

struct ColorHealthOptions {
  int frames_to_change = 30;      // team and side states (half a second at 60 fps)
  int ball_frames_to_change = 120;
  int min_other_team = 3;         // robots of the other team that make a team's absence telling
  int min_robots_for_ball = 3;
  int min_side_blobs = 8;
  double cast_change = 0.1;       // relative change of a white balance gain that is reported
};

class ColorHealthWatch {
 public:
  explicit ColorHealthWatch(const ColorHealthOptions& o = {}) : opt_(o) {}
  // One frame's record. Returns the issues whose state changed (bit
  // 1 << int(issue)); castChanged() tells whether the cast is to be said.
  unsigned update(const DetectionHealth& h);
  bool active(ColorIssue i) const { return state_[static_cast<int>(i)].active; }
  // Frames whose record showed the issue's evidence (the summary's counter).
  long evidenceFrames(ColorIssue i) const { return state_[static_cast<int>(i)].evidence_total; }
  long frames() const { return frames_; }
  // "yellow team not seen for 30 frames while 8 blue robots are (yellow-blue
  // separation 12.3)", or its end.
  std::string describe(ColorIssue i) const;
  bool castChanged() const { return cast_changed_; }
  // "white lines read R 163 G 217 B 195: white balance gains R x1.33 G x1.00 B x1.11".
  std::string describeCast() const;
  // The summary line: counts of frames with each issue's evidence; empty when none.
  std::string summary() const;
  static const char* name(ColorIssue i);
  // Calls say(warning, text) for each issue in `changed` (warning: it began)
  // and for the cast when castChanged().
  template <class Say>
  void sayChanges(unsigned changed, Say&& say) const {
    for (int i = 0; i < kColorIssueCount; ++i)
      if (changed >> i & 1) say(state_[i].active, describe(static_cast<ColorIssue>(i)));
    if (cast_changed_) say(false, describeCast());
  }

 private:
  struct State {
    bool active = false;
    int run = 0;  // consecutive frames disagreeing with `active`
    long evidence_total = 0;
  };
  ColorHealthOptions opt_;
  State state_[kColorIssueCount];
  DetectionHealth last_;   // the frame that changed a state last
  long frames_ = 0;
  bool cast_changed_ = false;
  bool cast_said_ = false;
  float cast_gain_[3] = {1, 1, 1};
  float cast_rgb_[3] = {0, 0, 0};
};

}  // namespace dv

#pragma once
// Progress of a long offline run on the terminal: frames done of total,
// frames per second and time left, redrawn at most 4 times a second on one
// line of stderr. Off when stderr is not a terminal (logs, CI) or --quiet.
#include <unistd.h>

#include <chrono>
#include <cstdio>

namespace dv::app {

class RunProgress {
 public:
  RunProgress(long total, bool wanted) : total_(total), on_(wanted && isatty(STDERR_FILENO)) {}

  void update(long done) {
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    const double s = std::chrono::duration<double>(now - start_).count();
    const double fps = s > 0 ? done / s : 0;
    if (total_ > 0) {
      const double left = fps > 0 ? (total_ - done) / fps : 0;
      std::fprintf(stderr, "\r  %ld of %ld frames, %.1f fps, %d:%02d left   ", done, total_, fps,
                   static_cast<int>(left) / 60, static_cast<int>(left) % 60);
    } else {
      std::fprintf(stderr, "\r  %ld frames, %.1f fps   ", done, fps);
    }
    drawn_ = true;
  }

  void finish() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
  }

 private:
  long total_;
  bool on_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace dv::app

#pragma once
// The last lines serve logged, kept in memory for the console's Status
// page; each line has its Unix time and a number that only grows, so a
// page asks for what is new since the last it saw. Thread-safe.
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace dv::app {

class LogRing {
 public:
  explicit LogRing(size_t capacity = 500) : capacity_(capacity) {}
  struct Line {
    uint64_t seq = 0;
    double t_unix = 0;
    std::string text;
    bool warning = false;  // a problem, not a note (see isWarningLine)
  };
  void add(const std::string& text);
  // Lines with seq > after, oldest first.
  std::vector<Line> since(uint64_t after) const;

 private:
  size_t capacity_;
  mutable std::mutex mutex_;
  std::deque<Line> lines_;
  uint64_t next_seq_ = 1;
};

// serve logs problems and notes alike; these words mark a problem.
bool isWarningLine(const std::string& text);

}  // namespace dv::app

#include "app/log_ring.h"

#include <algorithm>
#include <cctype>

#include "core/clock.h"

namespace dv::app {

bool isWarningLine(const std::string& text) {
  static const char* kWords[] = {"cannot", "not ", "refused", "lost", "failed", "error", "no ",
                                 "dropped", "unknown", "degraded", "stale", "could not", "skipped"};
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  return std::any_of(std::begin(kWords), std::end(kWords),
                     [&](const char* w) { return lower.find(w) != std::string::npos; });
}

void LogRing::add(const std::string& text) {
  Line l;
  l.t_unix = unixSeconds();
  l.text = text;
  l.warning = isWarningLine(text);
  std::lock_guard<std::mutex> lock(mutex_);
  l.seq = next_seq_++;
  lines_.push_back(std::move(l));
  while (lines_.size() > capacity_) lines_.pop_front();
}

std::vector<LogRing::Line> LogRing::since(uint64_t after) const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<Line> out;
  for (const Line& l : lines_)
    if (l.seq > after) out.push_back(l);
  return out;
}

}  // namespace dv::app

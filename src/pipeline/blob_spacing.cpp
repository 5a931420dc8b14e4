#include "pipeline/blob_spacing.h"

#include <algorithm>
#include <cmath>

namespace dv {

void BlobSpacing::configure(int width, int height, double min_distance, int capacity) {
  distance_ = min_distance;
  cell_ = std::max(min_distance, 1e-3);
  min_d2_ = min_distance * min_distance;
  bw_ = std::max(1, static_cast<int>(std::ceil(width / cell_)));
  bh_ = std::max(1, static_cast<int>(std::ceil(height / cell_)));
  head_.assign(static_cast<size_t>(bw_) * bh_, -1);
  next_.clear(), x_.clear(), y_.clear(), touched_.clear();
  next_.reserve(capacity), x_.reserve(capacity), y_.reserve(capacity), touched_.reserve(capacity);
}

void BlobSpacing::clear() {
  for (int b : touched_) head_[b] = -1;
  touched_.clear(), next_.clear(), x_.clear(), y_.clear();
}

int BlobSpacing::bucket(double x, double y) const {
  // Clamping keeps positions at or past the border in the edge buckets; it is
  // monotone, so neighbours within one bucket stay within one.
  const int bx = std::clamp(static_cast<int>(std::floor(x / cell_)), 0, bw_ - 1);
  const int by = std::clamp(static_cast<int>(std::floor(y / cell_)), 0, bh_ - 1);
  return by * bw_ + bx;
}

bool BlobSpacing::nearKept(double x, double y) const {
  const int b = bucket(x, y);
  const int bx = b % bw_, by = b / bw_;
  for (int yy = std::max(0, by - 1); yy <= std::min(bh_ - 1, by + 1); ++yy)
    for (int xx = std::max(0, bx - 1); xx <= std::min(bw_ - 1, bx + 1); ++xx)
      for (int i = head_[yy * bw_ + xx]; i >= 0; i = next_[i]) {
        const double dx = x_[i] - x, dy = y_[i] - y;
        if (dx * dx + dy * dy < min_d2_) return true;
      }
  return false;
}

void BlobSpacing::keep(double x, double y) {
  const int b = bucket(x, y);
  if (head_[b] < 0) touched_.push_back(b);
  next_.push_back(head_[b]);
  head_[b] = static_cast<int>(x_.size());
  x_.push_back(x), y_.push_back(y);
}

}  // namespace dv

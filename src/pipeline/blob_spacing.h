#pragma once
// One blob per object: peaks are taken strongest first, and one within
// kMinBlobDistanceMm of a blob already kept is a second maximum of that blob.
// Kept blobs sit in buckets of that size, so each test reads the 3 x 3
// buckets around the peak instead of every blob kept (weak peaks can number
// in the thousands on a noisy carpet). Both backends select through it.
#include <vector>

namespace dv {

class BlobSpacing {
 public:
  // Once per camera: a grid of width x height cells, the distance in cells,
  // and how many blobs a frame may keep (storage reserved for them).
  void configure(int width, int height, double min_distance, int capacity);
  // Forgets the blobs kept (start of a frame).
  void clear();
  // True when a kept blob lies closer than the distance to (x, y).
  bool nearKept(double x, double y) const;
  void keep(double x, double y);
  double distance() const { return distance_; }

 private:
  int bucket(double x, double y) const;

  double distance_ = 1, cell_ = 1, min_d2_ = 1;
  int bw_ = 1, bh_ = 1;
  std::vector<int> head_;     // per bucket: last blob kept in it, or -1
  std::vector<int> next_;     // per blob: the previous blob of its bucket
  std::vector<double> x_, y_;
  std::vector<int> touched_;  // buckets to reset in clear()
};

}  // namespace dv

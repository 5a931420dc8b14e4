#pragma once
// Range queries over one frame's blob positions with nanoflann's KD-tree
// (thesis A.5). The point storage and the result buffer are kept between
// frames; nanoflann's node pool is the only thing rebuilt per frame.
#include <nanoflann.hpp>

#include <memory>
#include <utility>
#include <vector>

#include "core/units.h"

namespace dv {

class BlobIndex {
 public:
  BlobIndex() { points_.reserve(1024), hits_.reserve(256); }

  // Positions to index; the vector is owned by the index and reused.
  std::vector<FieldMm>& points() { return points_; }

  void build() {
    if (!tree_) {
      tree_ = std::make_unique<Tree>(2, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(
                                                      10, nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex));
    }
    tree_->buildIndex();
  }

  // Indices (and squared distances) of points within `radius` of `p`,
  // valid until the next query.
  const std::vector<std::pair<size_t, double>>& within(const FieldMm& p, double radius) {
    hits_.clear();
    if (points_.empty()) return hits_;
    const double q[2] = {p.x, p.y};
    nanoflann::RadiusResultSet<double, size_t> result(radius * radius, hits_);
    tree_->radiusSearchCustomCallback(q, result, nanoflann::SearchParams(32, 0, false));
    return hits_;
  }

 private:
  struct Adaptor {
    const std::vector<FieldMm>* pts;
    size_t kdtree_get_point_count() const { return pts->size(); }
    double kdtree_get_pt(size_t i, size_t dim) const { return dim == 0 ? (*pts)[i].x : (*pts)[i].y; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Adaptor>,
                                                   Adaptor, 2>;

  std::vector<FieldMm> points_;
  Adaptor adaptor_{&points_};
  std::unique_ptr<Tree> tree_;
  std::vector<std::pair<size_t, double>> hits_;
};

}  // namespace dv

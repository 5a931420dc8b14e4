#include "geometry/calibration/line_groups.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>

namespace dv {

double LineSegment::length() const { return std::hypot(b.u - a.u, b.v - a.v); }

double LineSegment::angle() const {
  double t = std::atan2(b.v - a.v, b.u - a.u);
  if (t < 0) t += kPi;
  if (t >= kPi) t -= kPi;
  return t;
}

std::vector<LineSegment> detectLineSegments(const cv::Mat& line_mask) {
  // The mask is binary; a light blur gives LSD gradients to follow.
  cv::Mat smooth;
  cv::GaussianBlur(line_mask, smooth, cv::Size(5, 5), 1.0);
  auto lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  std::vector<cv::Vec4f> raw;
  lsd->detect(smooth, raw);
  std::vector<LineSegment> out;
  out.reserve(raw.size());
  for (const auto& l : raw) out.push_back({{l[0], l[1]}, {l[2], l[3]}});
  return out;
}

namespace {

double angleDifference(double a, double b) {
  double d = std::abs(a - b);
  return std::min(d, kPi - d);
}

// Distance of point p from the infinite line through s.
double perpendicularDistance(const LineSegment& s, ImagePx p) {
  const double dx = s.b.u - s.a.u, dy = s.b.v - s.a.v;
  const double len = std::hypot(dx, dy);
  if (len <= 0) return std::hypot(p.u - s.a.u, p.v - s.a.v);
  return std::abs((p.u - s.a.u) * dy - (p.v - s.a.v) * dx) / len;
}

double nearestEndpointGap(const LineSegment& s, const LineSegment& t) {
  auto d = [](ImagePx p, ImagePx q) { return std::hypot(p.u - q.u, p.v - q.v); };
  return std::min({d(s.a, t.a), d(s.a, t.b), d(s.b, t.a), d(s.b, t.b)});
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

}  // namespace

std::vector<LineGroup> groupSegments(const std::vector<LineSegment>& all,
                                     const SegmentGroupingOptions& o) {
  std::vector<LineSegment> segs;
  for (const auto& s : all)
    if (s.length() >= o.min_length_px) segs.push_back(s);
  UnionFind uf(segs.size());
  for (size_t i = 0; i < segs.size(); ++i) {
    for (size_t j = i + 1; j < segs.size(); ++j) {
      if (angleDifference(segs[i].angle(), segs[j].angle()) > o.max_angle_rad) continue;
      if (nearestEndpointGap(segs[i], segs[j]) >= o.max_endpoint_gap_px) continue;
      // Symmetric: the larger of both segments' midpoints' distances to the other.
      const ImagePx mi{(segs[i].a.u + segs[i].b.u) / 2, (segs[i].a.v + segs[i].b.v) / 2};
      const ImagePx mj{(segs[j].a.u + segs[j].b.u) / 2, (segs[j].a.v + segs[j].b.v) / 2};
      const double perp = std::max(perpendicularDistance(segs[i], mj), perpendicularDistance(segs[j], mi));
      if (perp >= o.max_perpendicular_px) continue;
      uf.join(int(i), int(j));
    }
  }
  std::vector<int> index_of_root(segs.size(), -1);
  std::vector<LineGroup> groups;
  for (size_t i = 0; i < segs.size(); ++i) {
    const int r = uf.find(int(i));
    if (index_of_root[r] < 0) {
      index_of_root[r] = int(groups.size());
      groups.emplace_back();
    }
    groups[index_of_root[r]].segments.push_back(segs[i]);
  }
  for (auto& g : groups) {
    std::vector<ImagePx> ends;
    for (const auto& s : g.segments) ends.push_back(s.a), ends.push_back(s.b);
    double best = 0;
    for (size_t i = 0; i < ends.size(); ++i)
      for (size_t j = i + 1; j < ends.size(); ++j)
        best = std::max(best, std::hypot(ends[i].u - ends[j].u, ends[i].v - ends[j].v));
    g.extent_px = best;
  }
  std::sort(groups.begin(), groups.end(),
            [](const LineGroup& a, const LineGroup& b) { return a.extent_px > b.extent_px; });
  return groups;
}

void collectGroupPixels(std::vector<LineGroup>& groups, const cv::Mat& line_mask, double band_px,
                        size_t max_per_group) {
  // Paint each group's band into a label image. A pixel at a crossing
  // belongs to two lines, so pixels in two bands are left out.
  cv::Mat label(line_mask.size(), CV_16UC1, cv::Scalar(0));
  cv::Mat count(line_mask.size(), CV_8UC1, cv::Scalar(0));
  const int thickness = std::max(1, int(std::lround(2 * band_px + 1)));
  for (size_t gi = 0; gi < groups.size() && gi < 65534; ++gi) {
    cv::Mat own(line_mask.size(), CV_8UC1, cv::Scalar(0));
    for (const auto& s : groups[gi].segments)
      cv::line(own, cv::Point(int(std::lround(s.a.u)), int(std::lround(s.a.v))),
               cv::Point(int(std::lround(s.b.u)), int(std::lround(s.b.v))), cv::Scalar(1), thickness);
    label.setTo(cv::Scalar(double(gi + 1)), own);
    cv::add(count, own, count);
  }
  std::vector<std::vector<ImagePx>> found(groups.size());
  for (int y = 0; y < line_mask.rows; ++y) {
    const uint8_t* m = line_mask.ptr<uint8_t>(y);
    const uint16_t* l = label.ptr<uint16_t>(y);
    const uint8_t* c = count.ptr<uint8_t>(y);
    for (int x = 0; x < line_mask.cols; ++x)
      if (m[x] && l[x] && c[x] == 1) found[l[x] - 1].push_back({double(x), double(y)});
  }
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    auto& src = found[gi];
    auto& dst = groups[gi].pixels;
    dst.clear();
    const double stride = std::max(1.0, double(src.size()) / double(std::max<size_t>(1, max_per_group)));
    for (double i = 0; i < double(src.size()) && dst.size() < max_per_group; i += stride)
      dst.push_back(src[size_t(i)]);
  }
}

}  // namespace dv

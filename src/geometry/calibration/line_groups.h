#pragma once
// Line segments on the line-pixel mask (OpenCV's LSD) and their grouping into
// field lines after Thormählen (thesis §5.1.6): segments are joined when
// their orientations differ by at most 3°, their perpendicular distance is
// under 10 px and their nearest endpoints are closer than 200 px. Segments
// under 10 px are dropped as their orientation is unstable.
#include <opencv2/core.hpp>
#include <vector>

#include "core/units.h"

namespace dv {

struct LineSegment {
  ImagePx a, b;
  double length() const;
  double angle() const;  // direction in [0, pi)
};

struct SegmentGroupingOptions {
  double min_length_px = 10;
  double max_angle_rad = 3.0 * 3.14159265358979323846 / 180;
  double max_perpendicular_px = 10;
  double max_endpoint_gap_px = 200;
};

struct LineGroup {
  std::vector<LineSegment> segments;
  // Largest distance between two endpoints of its segments.
  double extent_px = 0;
  // Line pixels (from the mask) within the group's band.
  std::vector<ImagePx> pixels;
};

// LSD on the mask (255 = line pixel).
std::vector<LineSegment> detectLineSegments(const cv::Mat& line_mask);

// Thormählen grouping; groups keep their member segments, sorted by extent
// (longest first).
std::vector<LineGroup> groupSegments(const std::vector<LineSegment>& segments,
                                     const SegmentGroupingOptions& options = {});

// Fills each group's pixels with the mask pixels within `band_px` of one of
// its segments, at most `max_per_group` spread along the group.
void collectGroupPixels(std::vector<LineGroup>& groups, const cv::Mat& line_mask, double band_px,
                        size_t max_per_group);

}  // namespace dv

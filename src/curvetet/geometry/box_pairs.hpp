#pragma once
// Candidate pairs of overlapping axis-aligned boxes (CGAL's box_intersection_d
// underneath: O(n log^3 n), no tuning). Used to find the few triangle pairs
// an exact intersection test must look at.
#include <Eigen/Core>

#include <utility>
#include <vector>

namespace curvetet::geometry {

struct Box3 {
  Eigen::Vector3d min;
  Eigen::Vector3d max;
};

// Closed boxes: touching counts.
inline bool boxes_overlap(const Box3& a, const Box3& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

// Box of a set of points, closed.
Box3 bounding_box(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// All pairs (i, j), i < j, of boxes in one set that overlap (closed boxes, so
// touching counts). Each pair once, in no particular order.
std::vector<std::pair<int, int>> overlapping_pairs(const std::vector<Box3>& boxes);

// All pairs (i in a, j in b) that overlap. Sorted, no duplicates.
std::vector<std::pair<int, int>> overlapping_pairs(const std::vector<Box3>& a, const std::vector<Box3>& b);

} // namespace curvetet::geometry

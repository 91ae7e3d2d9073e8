#include "curvetet/geometry/box_pairs.hpp"

#include <CGAL/box_intersection_d.h>

#include <algorithm>

namespace curvetet::geometry {
namespace {
using CgalBox = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, std::ptrdiff_t,
                                                            CGAL::Box_intersection_d::ID_EXPLICIT>;

std::vector<CgalBox> to_cgal(const std::vector<Box3>& boxes) {
  std::vector<CgalBox> out;
  out.reserve(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const auto& b = boxes[i];
    double lo[3] = {b.min.x(), b.min.y(), b.min.z()};
    double hi[3] = {b.max.x(), b.max.y(), b.max.z()};
    out.emplace_back(lo, hi, static_cast<std::ptrdiff_t>(i));
  }
  return out;
}

void sort_unique(std::vector<std::pair<int, int>>& pairs) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}
} // namespace

Box3 bounding_box(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
}

std::vector<std::pair<int, int>> overlapping_pairs(const std::vector<Box3>& boxes) {
  auto cb = to_cgal(boxes);
  std::vector<std::pair<int, int>> pairs;
  CGAL::box_self_intersection_d(cb.begin(), cb.end(), [&](const CgalBox& x, const CgalBox& y) {
    auto i = static_cast<int>(x.handle()), j = static_cast<int>(y.handle());
    pairs.emplace_back(std::min(i, j), std::max(i, j));
  });
  return pairs;
}

std::vector<std::pair<int, int>> overlapping_pairs(const std::vector<Box3>& a, const std::vector<Box3>& b) {
  auto ca = to_cgal(a);
  auto cb = to_cgal(b);
  std::vector<std::pair<int, int>> pairs;
  CGAL::box_intersection_d(ca.begin(), ca.end(), cb.begin(), cb.end(), [&](const CgalBox& x, const CgalBox& y) {
    pairs.emplace_back(static_cast<int>(x.handle()), static_cast<int>(y.handle()));
  });
  sort_unique(pairs);
  return pairs;
}

} // namespace curvetet::geometry

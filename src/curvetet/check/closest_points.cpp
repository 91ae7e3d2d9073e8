#include "curvetet/check/closest_points.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

namespace curvetet::check {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle = K::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
} // namespace

std::vector<ClosestPoint> closest_points(const mesh::SurfaceMesh& s, const std::vector<mesh::Vec3>& queries) {
  std::vector<ClosestPoint> out(queries.size());
  if (s.faces.empty()) return out;
  std::vector<Triangle> tris;
  tris.reserve(s.faces.size());
  auto pt = [](const mesh::Vec3& p) { return K::Point_3(p.x(), p.y(), p.z()); };
  for (const auto& f : s.faces) tris.emplace_back(pt(s.vertices[f[0]]), pt(s.vertices[f[1]]), pt(s.vertices[f[2]]));
  Tree tree(tris.begin(), tris.end());
  tree.accelerate_distance_queries();
  tbb::parallel_for(std::size_t(0), queries.size(), [&](std::size_t i) {
    const auto [p, it] = tree.closest_point_and_primitive(pt(queries[i]));
    out[i].face = static_cast<int>(it - tris.begin());
    out[i].point = mesh::Vec3(p.x(), p.y(), p.z());
  });
  return out;
}

std::vector<double> distances_to_surface(const mesh::SurfaceMesh& s, const std::vector<mesh::Vec3>& queries) {
  const auto closest = closest_points(s, queries);
  std::vector<double> out(queries.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < queries.size(); ++i)
    if (closest[i].face >= 0) out[i] = (closest[i].point - queries[i]).norm();
  return out;
}

} // namespace curvetet::check

#include "curvetet/shell/local_thickness.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

namespace curvetet::shell {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
using Traits = CGAL::AABB_traits<Kernel, Primitive>;

struct ThicknessProbe::Tree {
  std::vector<Triangle> triangles;
  CGAL::AABB_tree<Traits> tree;
};

namespace {
Kernel::Point_3 point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
} // namespace

ThicknessProbe::ThicknessProbe(const mesh::SurfaceMesh& input) : tree_(std::make_unique<Tree>()) {
  for (const auto& f : input.faces)
    tree_->triangles.emplace_back(point(input.vertices[f[0]]), point(input.vertices[f[1]]), point(input.vertices[f[2]]));
  tree_->tree.insert(tree_->triangles.begin(), tree_->triangles.end());
  tree_->tree.build();
}

ThicknessProbe::~ThicknessProbe() = default;

double ThicknessProbe::depth(const Vec3& p, const Vec3& d, double skip) const {
  // Start past the faces around p: the first hit after that is the far side.
  const Vec3 start = p + skip * d;
  const Kernel::Ray_3 ray(point(start), Kernel::Vector_3(d.x(), d.y(), d.z()));
  const auto hit = tree_->tree.first_intersection(ray);
  if (!hit) return std::numeric_limits<double>::infinity();
  double nearest = std::numeric_limits<double>::infinity();
  if (const auto* q = boost::get<Kernel::Point_3>(&hit->first)) {
    nearest = std::sqrt(CGAL::squared_distance(*q, ray.source()));
  } else if (const auto* e = boost::get<Kernel::Segment_3>(&hit->first)) { // ray in the triangle's plane
    nearest = std::sqrt(std::min(CGAL::squared_distance(e->source(), ray.source()),
                                 CGAL::squared_distance(e->target(), ray.source())));
  }
  return nearest + skip;
}

std::vector<double> ThicknessProbe::at_vertices(const Shell& s, double skip) const {
  std::vector<double> out(s.num_vertices(), std::numeric_limits<double>::infinity());
  tbb::parallel_for(0, s.num_vertices(), [&](int v) {
    const Vec3 inward = s.bottom[v] - s.top[v];
    if (s.singular[v] || !(inward.norm() > 0)) return;
    out[v] = depth(s.middle[v], inward.normalized(), skip);
  });
  return out;
}

} // namespace curvetet::shell

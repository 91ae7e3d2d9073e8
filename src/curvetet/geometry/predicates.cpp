#include "curvetet/geometry/predicates.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>

namespace curvetet::geometry {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
K::Point_3 cg(const Point3& p) { return {p.x(), p.y(), p.z()}; }
} // namespace

int orient3d_exact(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  // A repeated point: the determinant is identically zero. CGAL's interval
  // filter proves that only when a is repeated (the others leave two equal
  // rows, whose interval products do not cancel) and falls back to
  // multiprecision; the shell's checks pass shared corners millions of times.
  if (a == b || a == c || a == d || b == c || b == d || c == d) return 0;
  return static_cast<int>(CGAL::orientation(cg(a), cg(b), cg(c), cg(d)));
}

bool collinear(const Point3& a, const Point3& b, const Point3& c) { return CGAL::collinear(cg(a), cg(b), cg(c)); }

int coplanar_orientation(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return static_cast<int>(CGAL::coplanar_orientation(cg(a), cg(b), cg(c), cg(d)));
}

bool segment_triangle_intersect(const Point3& s0, const Point3& s1, const Point3& t0, const Point3& t1,
                                const Point3& t2) {
  return CGAL::do_intersect(K::Segment_3(cg(s0), cg(s1)), K::Triangle_3(cg(t0), cg(t1), cg(t2)));
}

bool triangles_intersect(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0, const Point3& b1,
                         const Point3& b2) {
  return CGAL::do_intersect(K::Triangle_3(cg(a0), cg(a1), cg(a2)), K::Triangle_3(cg(b0), cg(b1), cg(b2)));
}

namespace {
K::Point_2 drop(const Point3& p, int axis) {
  return axis == 0 ? K::Point_2(p.y(), p.z()) : axis == 1 ? K::Point_2(p.z(), p.x()) : K::Point_2(p.x(), p.y());
}
} // namespace

bool coplanar_segment_triangle_intersect(const Point3& s0, const Point3& s1, const Point3& t0, const Point3& t1,
                                         const Point3& t2) {
  // Any axis whose projection keeps the triangle non-degenerate is a bijection
  // of the common plane onto 2D; try the dominant normal axis first.
  Eigen::Vector3d n = (t1 - t0).cross(t2 - t0).cwiseAbs();
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int a, int b) { return n[a] > n[b]; });
  for (int axis : order) {
    K::Point_2 a = drop(t0, axis), b = drop(t1, axis), c = drop(t2, axis);
    auto o = CGAL::orientation(a, b, c);
    if (o == CGAL::COLLINEAR) continue;
    if (o == CGAL::CLOCKWISE) std::swap(b, c);
    const K::Point_2 p = drop(s0, axis), q = drop(s1, axis);
    // Separating-axis test for closed convex sets in 2D: the segment misses
    // the triangle iff both its ends are strictly outside one triangle edge,
    // or the whole triangle is strictly on one side of the segment's line.
    const K::Point_2 tri[3] = {a, b, c};
    for (int k = 0; k < 3; ++k)
      if (CGAL::orientation(tri[k], tri[(k + 1) % 3], p) == CGAL::CLOCKWISE &&
          CGAL::orientation(tri[k], tri[(k + 1) % 3], q) == CGAL::CLOCKWISE)
        return false;
    if (p == q) return true; // a point inside all three edges
    auto oa = CGAL::orientation(p, q, a), ob = CGAL::orientation(p, q, b), oc = CGAL::orientation(p, q, c);
    return !(oa == ob && ob == oc && oa != CGAL::COLLINEAR);
  }
  return segment_triangle_intersect(s0, s1, t0, t1, t2); // unreachable for a non-degenerate triangle
}

double triangle_area(const Point3& a, const Point3& b, const Point3& c) { return 0.5 * (b - a).cross(c - a).norm(); }

} // namespace curvetet::geometry

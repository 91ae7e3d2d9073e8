#include "curvetet/geometry/predicates.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

namespace curvetet::geometry {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
K::Point_3 cg(const Point3& p) { return {p.x(), p.y(), p.z()}; }
} // namespace

int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
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

double triangle_area(const Point3& a, const Point3& b, const Point3& c) { return 0.5 * (b - a).cross(c - a).norm(); }

} // namespace curvetet::geometry

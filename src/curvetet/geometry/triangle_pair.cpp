#include "curvetet/geometry/triangle_pair.hpp"

#include <algorithm>

namespace curvetet::geometry {
namespace {

// All of q strictly on one side of p's plane (three filtered orient3d): a
// cheap exact rejection that decides most disjoint pairs.
bool strictly_one_side(const std::array<Point3, 3>& p, const std::array<Point3, 3>& q) {
  const int o = orient3d(p[0], p[1], p[2], q[0]);
  return o != 0 && o == orient3d(p[0], p[1], p[2], q[1]) && o == orient3d(p[0], p[1], p[2], q[2]);
}

} // namespace

bool triangles_intersect_improperly(const std::array<Point3, 3>& a, const std::array<Point3, 3>& b,
                                    const SharedCorners& shared) {
  if (shared.count == 0) {
    if (strictly_one_side(a, b) || strictly_one_side(b, a)) return false;
    return triangles_intersect(a[0], a[1], a[2], b[0], b[1], b[2]);
  }
  if (shared.count == 1) {
    const int i = shared.a[0], j = shared.b[0];
    const Point3 &v = a[i], &a1 = a[(i + 1) % 3], &a2 = a[(i + 2) % 3];
    const Point3 &b1 = b[(j + 1) % 3], &b2 = b[(j + 2) % 3];
    // B strictly on one side of A's plane except at v (or vice versa): they
    // meet only at v. Cheap, and decides most neighbouring pairs.
    const int s1 = orient3d(v, a1, a2, b1), s2 = orient3d(v, a1, a2, b2);
    if (s1 == s2 && s1 != 0) return false;
    const int r1 = orient3d(v, b1, b2, a1), r2 = orient3d(v, b1, b2, a2);
    if (r1 == r2 && r1 != 0) return false;
    if (s1 == 0 && s2 == 0) // coplanar: decide in 2D
      return coplanar_segment_triangle_intersect(a1, a2, v, b1, b2) ||
             coplanar_segment_triangle_intersect(b1, b2, v, a1, a2);
    return segment_triangle_intersect(a1, a2, v, b1, b2) || segment_triangle_intersect(b1, b2, v, a1, a2);
  }
  if (shared.count == 2) {
    const Point3 &u = a[shared.a[0]], &v = a[shared.a[1]];
    const Point3 &pa = a[3 - shared.a[0] - shared.a[1]], &pb = b[3 - shared.b[0] - shared.b[1]];
    if (orient3d(u, v, pa, pb) != 0) return false;
    return coplanar_orientation(u, v, pa, pb) > 0;
  }
  return true;
}

} // namespace curvetet::geometry

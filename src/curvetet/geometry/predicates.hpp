#pragma once
// Exact geometric predicates on double coordinates (floating-point filter,
// exact fallback; CGAL's Epick underneath, never exposed).
//
// Orientation convention, used everywhere in curvetet:
//   orient3d(a, b, c, d) = sign( det[ b-a, c-a, d-a ] )
// so the right-handed unit tet (0,0,0),(1,0,0),(0,1,0),(0,0,1) is +1 (like
// geogram; the opposite of Shewchuk's orient3d). A tet (a,b,c,d) is
// "positive" when orient3d > 0: seen from d, the triangle a,b,c turns
// counter-clockwise. Pinned by tests/geometry/test_predicates.cpp.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace curvetet::geometry {

using Point3 = Eigen::Vector3d;

// -1, 0 or +1 exactly, decided by CGAL (its own filter, then exact).
int orient3d_exact(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

// -1, 0 or +1 exactly. Inline, with a floating-point filter in front of
// orient3d_exact(): the volume code calls it millions of times, and the
// call into CGAL cost more than the filter itself.
inline int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  // det[b-a, c-a, d-a] as in Shewchuk's orient3d (rows u, v, w), whose
  // error is at most (7 + 56 eps) eps times the permanent below. The
  // differences are kept below 1e100 (no overflow); underflowed products,
  // then multiplied by at most 1e100, add under 1e-222 in all.
  const double ux = b.x() - a.x(), uy = b.y() - a.y(), uz = b.z() - a.z();
  const double vx = c.x() - a.x(), vy = c.y() - a.y(), vz = c.z() - a.z();
  const double wx = d.x() - a.x(), wy = d.y() - a.y(), wz = d.z() - a.z();
  const double vxwy = vx * wy, wxvy = wx * vy, wxuy = wx * uy, uxwy = ux * wy, uxvy = ux * vy, vxuy = vx * uy;
  const double det = uz * (vxwy - wxvy) + vz * (wxuy - uxwy) + wz * (uxvy - vxuy);
  const double permanent = (std::abs(vxwy) + std::abs(wxvy)) * std::abs(uz) +
                           (std::abs(wxuy) + std::abs(uxwy)) * std::abs(vz) +
                           (std::abs(uxvy) + std::abs(vxuy)) * std::abs(wz);
  constexpr double kEps = 0x1p-53;
  constexpr double kBound = (7.0 + 56.0 * kEps) * kEps;
  const double largest = std::max({std::abs(ux), std::abs(uy), std::abs(uz), std::abs(vx), std::abs(vy),
                                   std::abs(vz), std::abs(wx), std::abs(wy), std::abs(wz)});
  if (largest <= 1e100) { // false for NaN too
    const double bound = kBound * permanent + 1e-222;
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  return orient3d_exact(a, b, c, d);
}

// Exact: a, b, c lie on one line (including coincident points).
bool collinear(const Point3& a, const Point3& b, const Point3& c);

// For coplanar a, b, c, d (caller guarantees): +1 if c and d are strictly on
// the same side of line ab within the plane, -1 if on opposite sides, 0 if
// either is on the line. Precondition: a, b, c not collinear.
int coplanar_orientation(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

// Exact intersection tests on closed, non-degenerate triangles/segments.
bool segment_triangle_intersect(const Point3& s0, const Point3& s1, const Point3& t0, const Point3& t1,
                                const Point3& t2);
bool triangles_intersect(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0, const Point3& b1,
                         const Point3& b2);

// For coplanar inputs only (caller guarantees, e.g. by orient3d == 0): exact
// closed segment-triangle intersection decided in 2D on the plane's dominant
// projection (dropping a coordinate is exact). Much faster than the 3D test
// on coplanar data, where every 3D orientation is an exact zero.
// Precondition: the triangle is not degenerate.
bool coplanar_segment_triangle_intersect(const Point3& s0, const Point3& s1, const Point3& t0, const Point3& t1,
                                         const Point3& t2);

// Exact sign of the squared-area comparison is not needed elsewhere; this is
// the plain double area, for reporting only (never for a decision).
double triangle_area(const Point3& a, const Point3& b, const Point3& c);

} // namespace curvetet::geometry

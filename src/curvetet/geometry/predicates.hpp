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

namespace curvetet::geometry {

using Point3 = Eigen::Vector3d;

// -1, 0 or +1 exactly.
int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

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

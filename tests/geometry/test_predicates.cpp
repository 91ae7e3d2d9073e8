#include "curvetet/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>

using curvetet::geometry::Point3;
namespace g = curvetet::geometry;

// Pins the orientation convention documented in predicates.hpp.
TEST(Orient3d, RightHandedUnitTetIsPositive) {
  Point3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  EXPECT_EQ(g::orient3d(o, x, y, z), 1);
  EXPECT_EQ(g::orient3d(o, y, x, z), -1);
  EXPECT_EQ(g::orient3d(o, x, y, Point3(5, -3, 0)), 0);
}

TEST(Orient3d, ExactWhereDoublesRoundWrongly) {
  // d is off the plane by one ulp-scale amount that a naive determinant in
  // double arithmetic loses among large terms.
  Point3 a(1e8, 1e8, 0), b(1e8 + 1, 1e8, 0), c(1e8, 1e8 + 1, 0);
  Point3 d(0.5, 0.5, 1e-300);
  EXPECT_EQ(g::orient3d(a, b, c, d), 1);
  EXPECT_EQ(g::orient3d(a, b, c, Point3(0.5, 0.5, -1e-300)), -1);
  EXPECT_EQ(g::orient3d(a, b, c, Point3(0.5, 0.5, 0.0)), 0);
}

// The inline filter must never decide differently from the exact
// predicate: points on small integer grids (many exact zeros), then nudged
// off their plane by one ulp, at scales from 1e-200 to 1e+160 (underflow
// and overflow of the filter's products), and NaN.
TEST(Orient3d, FilterAgreesWithExactOnNearDegenerateInput) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> grid(-3, 3);
  std::uniform_real_distribution<double> weight(-1, 1);
  int zeros = 0;
  for (int k = 0; k < 200000; ++k) {
    Point3 a(grid(rng), grid(rng), grid(rng)), b(grid(rng), grid(rng), grid(rng)), c(grid(rng), grid(rng), grid(rng));
    Point3 d = a + weight(rng) * (b - a) + weight(rng) * (c - a);
    if (k % 3 == 0) d.x() = std::nextafter(d.x(), 1e300);
    const double scale = std::pow(10.0, 60 * (k % 7) - 200);
    a *= scale;
    b *= scale;
    c *= scale;
    d *= scale;
    const int exact = g::orient3d_exact(a, b, c, d);
    zeros += exact == 0;
    ASSERT_EQ(g::orient3d(a, b, c, d), exact) << "case " << k;
  }
  EXPECT_GT(zeros, 10000); // the degenerate cases were really exercised
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Point3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), q(nan, 0, 1);
  EXPECT_EQ(g::orient3d(o, x, y, q), g::orient3d_exact(o, x, y, q));
}

// A repeated point gives zero in any position; one ulp away from it the
// sign is that of the nudge's direction against the other three points.
TEST(Orient3d, RepeatedPointIsZeroAndOneUlpAwayIsNot) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-1, 1);
  for (int k = 0; k < 2000; ++k) {
    std::array<Point3, 4> p;
    for (auto& x : p) x = Point3(coord(rng), coord(rng), coord(rng));
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        if (i == j) continue;
        auto q = p;
        q[j] = q[i];
        ASSERT_EQ(g::orient3d(q[0], q[1], q[2], q[3]), 0) << i << j;
        ASSERT_EQ(g::orient3d_exact(q[0], q[1], q[2], q[3]), 0) << i << j;
        q[j].x() = std::nextafter(q[i].x(), 2.0);
        // Replacing q[j] by the direction e_x, from q[i]: the sign of the
        // determinant with that row (well away from zero for these points).
        auto r = q;
        r[j] = q[i] + Point3(1, 0, 0);
        const Point3 o = r[0];
        const double det = (r[1] - o).dot((r[2] - o).cross(r[3] - o));
        if (std::abs(det) < 1e-3) continue;
        ASSERT_EQ(g::orient3d(q[0], q[1], q[2], q[3]), det > 0 ? 1 : -1) << i << j;
      }
  }
}

TEST(Collinear, ExactOnCoincidentAndNearlyCollinearPoints) {
  Point3 a(0, 0, 0), b(1, 1, 1);
  EXPECT_TRUE(g::collinear(a, b, Point3(2, 2, 2)));
  EXPECT_TRUE(g::collinear(a, a, b));
  EXPECT_FALSE(g::collinear(a, b, Point3(2, 2, 2 + 4.440892098500626e-16)));
}

TEST(TriangleIntersection, TouchingAndSeparated) {
  Point3 a0(0, 0, 0), a1(1, 0, 0), a2(0, 1, 0);
  EXPECT_TRUE(g::triangles_intersect(a0, a1, a2, Point3(0.2, 0.2, -1), Point3(0.2, 0.2, 1), Point3(0.3, 0.4, 0)));
  EXPECT_FALSE(g::triangles_intersect(a0, a1, a2, Point3(0, 0, 1e-300), Point3(1, 0, 1e-300), Point3(0, 1, 1e-300)));
  // Vertex touching an edge counts as intersecting (closed triangles).
  EXPECT_TRUE(g::triangles_intersect(a0, a1, a2, Point3(0.5, 0.5, 0), Point3(1, 1, 1), Point3(1, 1, -1)));
}

TEST(SegmentTriangle, Basic) {
  Point3 t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  EXPECT_TRUE(g::segment_triangle_intersect(Point3(0.1, 0.1, -1), Point3(0.1, 0.1, 1), t0, t1, t2));
  EXPECT_FALSE(g::segment_triangle_intersect(Point3(0.6, 0.6, -1), Point3(0.6, 0.6, 1), t0, t1, t2));
}

TEST(CoplanarSegmentTriangle, AgreesWithTheGeneral3dTest) {
  // Points on a tilted plane z = x + 2y (exactly representable values), so
  // every configuration is exactly coplanar.
  auto on_plane = [](double x, double y) { return Point3(x, y, x + 2 * y); };
  const Point3 t0 = on_plane(0, 0), t1 = on_plane(4, 0), t2 = on_plane(0, 4);
  const double grid[] = {-1, 0, 0.5, 1, 2, 3, 4, 5};
  int hits = 0, misses = 0;
  for (double x0 : grid)
    for (double y0 : grid)
      for (double x1 : grid)
        for (double y1 : grid) {
          Point3 s0 = on_plane(x0, y0), s1 = on_plane(x1, y1);
          if (s0 == s1) continue; // CGAL requires a proper segment
          bool want = g::segment_triangle_intersect(s0, s1, t0, t1, t2);
          ASSERT_EQ(g::coplanar_segment_triangle_intersect(s0, s1, t0, t1, t2), want)
              << x0 << "," << y0 << " - " << x1 << "," << y1;
          (want ? hits : misses)++;
        }
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 100);
}

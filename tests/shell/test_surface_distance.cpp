// The boundary -> input bound of a middle patch (issue 26, ε both ways):
// it never falls below the patch's true distance to the input, is not much
// above it, and the closest point it measures to lies on the triangle even
// for a needle.
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/shell/surface_distance.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace curvetet;
using namespace curvetet::shell;

namespace {

// Lagrange nodes (internal order) of the cubic graph z = c u v (1 - u - v)
// over the unit triangle: zero on its edges, c/27 at its centroid.
std::vector<Vec3> bubble_nodes(double c) {
  std::vector<Vec3> nodes;
  for (int i = 0; i < highorder::triangle_node_count(3); ++i) {
    const auto q = highorder::triangle_node(3, i);
    const double u = q[0] / 3.0, v = q[1] / 3.0;
    nodes.push_back(Vec3(u, v, c * u * v * (1 - u - v)));
  }
  return nodes;
}

// The unit triangle in z = 0 as input, split in four.
mesh::SurfaceMesh flat_input() {
  mesh::SurfaceMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0, 0}, {0.5, 0.5, 0}, {0, 0.5, 0}};
  m.faces = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
  return m;
}

} // namespace

TEST(SurfaceDistance, BoundsTheBubbleFromAboveAndTightly) {
  const auto input = flat_input();
  const std::vector<int> faces = {0, 1, 2, 3};
  for (const double c : {0.0, 0.3, 1.0, -2.0}) {
    const double exact = std::abs(c) / 27; // the plane is below/above the peak
    for (const double eps : {0.5, 0.1}) {
      const auto d = patch_distance_bound(3, bubble_nodes(c), input, faces, eps);
      if (exact + 1e-12 > eps) {
        EXPECT_GT(d.bound(), eps) << c;
        continue;
      }
      EXPECT_LE(d.bound(), eps) << c << " " << eps;
      EXPECT_GE(d.bound(), exact) << c;
      EXPECT_LE(d.sampled, exact + 1e-15);
      EXPECT_GT(d.rounding, 0);
      EXPECT_LT(d.rounding, 1e-12);
    }
  }
}

TEST(SurfaceDistance, FlatTriangleOnItsInputIsWithinAFractionOfEpsilon) {
  const std::vector<Vec3> corners = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  // Input split in four: lattice cells across the input's edges take the
  // first-order bound.
  const auto split = patch_distance_bound(1, corners, flat_input(), std::vector<int>{0, 1, 2, 3}, 0.05);
  EXPECT_LT(split.sampled, 1e-15);
  EXPECT_LE(split.bound(), 0.05 / 2);
  // The input is the triangle itself: every cell lies on one input face,
  // whose distance is convex, so the bound is the rounding only, at any
  // epsilon.
  mesh::SurfaceMesh one;
  one.vertices = corners;
  one.faces = {{0, 1, 2}};
  const auto same = patch_distance_bound(1, corners, one, std::vector<int>{0}, 1e-9);
  EXPECT_EQ(same.sampled, 0);
  EXPECT_EQ(same.between, 0);
  EXPECT_LE(same.bound(), 1e-13);
}

TEST(SurfaceDistance, RefinesTheLatticeWhenOnlyTheGapBetweenSamplesMisses) {
  const auto input = flat_input();
  const std::vector<int> faces = {0, 1, 2, 3};
  // Peak 3/27 = 0.111 with epsilon 0.14: the first lattice allows epsilon/4
  // between samples, which leaves too little beside the peak.
  const auto d = patch_distance_bound(3, bubble_nodes(3), input, faces, 0.14);
  EXPECT_LE(d.bound(), 0.14);
  EXPECT_LT(d.between, 0.14 - 3.0 / 27);
}

TEST(SurfaceDistance, NoInputFacesMeansUnbounded) {
  const auto d = patch_distance_bound(3, bubble_nodes(0), flat_input(), {}, 1);
  EXPECT_GT(d.bound(), 1);
}

TEST(SurfaceDistance, ClosestPointStaysOnANeedle) {
  // A needle 1e-17 high: the plane projection is meaningless, the edges are not.
  const Vec3 a(0, 0, 0), b(10, 0, 0), c(5, 1e-17, 0);
  const Vec3 p(3, 2, 0.5);
  const Vec3 q = closest_point_on_triangle(p, a, b, c);
  EXPECT_NEAR(q.x(), 3, 1e-12);
  EXPECT_NEAR(q.y(), 0, 1e-12);
  EXPECT_EQ(q.z(), 0);
  // Inside a regular triangle: the foot of the perpendicular.
  const Vec3 r = closest_point_on_triangle(Vec3(0.2, 0.2, 1), a, Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_NEAR((r - Vec3(0.2, 0.2, 0)).norm(), 0, 1e-15);
}

// The early probes agree with the full bound: a patch they fail has a bound
// above epsilon, and every patch whose bound is within epsilon passes them.
TEST(SurfaceDistance, ProbesFailOnlyPatchesTheBoundFails) {
  const auto input = flat_input();
  const std::vector<int> faces = {0, 1, 2, 3};
  int failed_early = 0;
  for (const double c : {0.0, 0.3, 1.0, 2.0, 2.9, 3.0, 3.1, -4.0, 8.0})
    for (const double eps : {0.5, 0.14, 0.1, 0.05, 0.01}) {
      const PatchDistanceCheck check(3, bubble_nodes(c), input, faces, eps);
      const auto d = check.bound();
      EXPECT_EQ(d.bound(), patch_distance_bound(3, bubble_nodes(c), input, faces, eps).bound());
      if (check.fails_early()) {
        ++failed_early;
        EXPECT_GT(d.bound(), eps) << c << " " << eps;
      }
      if (d.bound() <= eps) {
        EXPECT_FALSE(check.fails_early()) << c << " " << eps;
      }
    }
  EXPECT_GT(failed_early, 0); // the probes do reject the high bubbles
  EXPECT_TRUE(PatchDistanceCheck(3, bubble_nodes(0), input, {}, 1).fails_early());
}

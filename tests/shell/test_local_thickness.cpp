// The solid's thickness under the shell (shell/local_thickness.hpp): rays
// inward from the surface to its far side.
#include "curvetet/shell/local_thickness.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace curvetet;
using shell::Vec3;

namespace {

// The boundary of the box [0, a] x [0, 1] x [0, 1], outward triangles.
mesh::SurfaceMesh box(double a) {
  mesh::SurfaceMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1 ? a : 0, i & 2 ? 1 : 0, i & 4 ? 1 : 0);
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

} // namespace

TEST(LocalThickness, RayFromAFaceMeetsTheFarSide) {
  const shell::ThicknessProbe probe(box(10));
  EXPECT_NEAR(probe.depth(Vec3(5, 0, 0.5), Vec3(0, 1, 0), 0.01), 1.0, 1e-12);
  EXPECT_NEAR(probe.depth(Vec3(0, 0.5, 0.5), Vec3(1, 0, 0), 0.01), 10.0, 1e-12);
  // Diagonal from an edge of the long box: the far corner edge at sqrt(2).
  EXPECT_NEAR(probe.depth(Vec3(5, 0, 0), Vec3(0, 1, 1).normalized(), 0.01), std::sqrt(2.0), 1e-12);
}

TEST(LocalThickness, RayLeavingTheSolidMeetsNothing) {
  const shell::ThicknessProbe probe(box(10));
  EXPECT_TRUE(std::isinf(probe.depth(Vec3(5, 0, 0.5), Vec3(0, -1, 0), 0.01)));
}

#pragma once
// A one-tet shell for the assembly tests: the middle surface is the unit
// right tet (its edges optionally bulged), the bottom surface the same tet
// shrunk about its centroid.
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/volume/assemble.hpp"

#include <gtest/gtest.h>

namespace curvetet::test {

using mesh::Vec3;

// Middle = the unit right tet; bottom = the same shrunk towards its centroid
// (with `pinch0`, vertex 0 is kept in place: a singular vertex). Fill =
// the one bottom tet. Middle edges are bulged outward by `bulge` (degree 2
// patches, edge nodes shared by construction).
inline volume::CurvedMiddle tet_shell(double bulge, bool pinch0) {
  const std::vector<Vec3> middle = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const Vec3 centre(0.25, 0.25, 0.25);
  volume::CurvedMiddle s;
  for (const auto& p : middle) s.bottom.push_back(centre + 0.5 * (p - centre));
  s.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  s.singular = {char(pinch0), 0, 0, 0};
  if (pinch0) s.bottom[0] = middle[0];
  s.degree = bulge == 0 ? 1 : 2;
  const Vec3 g(0.25, 0.25, 0.25);
  for (const auto& f : s.faces) {
    std::vector<Vec3> nodes = {middle[f[0]], middle[f[1]], middle[f[2]]};
    if (s.degree == 2)
      for (int k = 0; k < 3; ++k) {
        Vec3 m = 0.5 * (middle[f[k]] + middle[f[(k + 1) % 3]]);
        nodes.push_back(m + bulge * (m - g));
      }
    s.middle_nodes.push_back(nodes);
  }
  return s;
}

inline mesh::LinearTetMesh bottom_fill(const volume::CurvedMiddle& s) {
  mesh::LinearTetMesh fill;
  fill.vertices = s.bottom;
  fill.tets = {{0, 1, 2, 3}};
  EXPECT_EQ(geometry::orient3d(s.bottom[0], s.bottom[1], s.bottom[2], s.bottom[3]), 1);
  return fill;
}

} // namespace curvetet::test

#pragma once
// A curved mesh with one nearly flat inner tet: a bad max AMIPS to improve
// (tests of curved_optimize, curved_remesh, curved_descent).
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/volume/assemble.hpp"

#include <gtest/gtest.h>

namespace curvetet::test {

// Middle = the unit right tet with edges bulged outward (degree 2 patches);
// bottom = the middle shrunk to half about its centroid; fill = the bottom
// tet split at an inner point pushed close to the bottom face (0, 2, 1):
// a flat tet there, so a bad max AMIPS to improve.
//
//        3            bottom tet (0,1,2,3) split at x:
//       /|\             (x,1,2,3) (0,x,2,3) (0,1,x,3) (0,1,2,x)
//      / x \            x near face (0,2,1) -> (0,1,2,x) is flat
//     0-----2
//      \ 1 /
inline mesh::TetMesh flat_inner_tet_mesh(int order) {
  const std::vector<mesh::Vec3> middle = {mesh::Vec3(0, 0, 0), mesh::Vec3(1, 0, 0), mesh::Vec3(0, 1, 0), mesh::Vec3(0, 0, 1)};
  const mesh::Vec3 centre(0.25, 0.25, 0.25);
  volume::CurvedMiddle s;
  for (const auto& p : middle) s.bottom.push_back(centre + 0.5 * (p - centre));
  s.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  s.singular = {0, 0, 0, 0};
  s.degree = 2;
  for (const auto& f : s.faces) {
    std::vector<mesh::Vec3> nodes = {middle[f[0]], middle[f[1]], middle[f[2]]};
    for (int k = 0; k < 3; ++k) {
      const mesh::Vec3 m = 0.5 * (middle[f[k]] + middle[f[(k + 1) % 3]]);
      nodes.push_back(m + 0.1 * (m - centre));
    }
    s.middle_nodes.push_back(nodes);
  }
  mesh::LinearTetMesh fill;
  fill.vertices = s.bottom;
  const mesh::Vec3 bottom_face_centre = (s.bottom[0] + s.bottom[1] + s.bottom[2]) / 3.0;
  fill.vertices.push_back(bottom_face_centre + 0.03 * (s.bottom[3] - bottom_face_centre));
  fill.tets = {{4, 1, 2, 3}, {0, 4, 2, 3}, {0, 1, 4, 3}, {0, 1, 2, 4}};
  for (const auto& t : fill.tets)
    EXPECT_EQ(geometry::orient3d(fill.vertices[t[0]], fill.vertices[t[1]], fill.vertices[t[2]], fill.vertices[t[3]]), 1);
  return volume::assemble_curved_mesh(s, fill, order);
}

} // namespace curvetet::test

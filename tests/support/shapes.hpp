#pragma once
// Tiny meshes built in code for tests. All closed shapes are oriented with
// outward normals (counter-clockwise seen from outside).
#include "curvetet/mesh/surface_mesh.hpp"

#include <algorithm>

namespace curvetet::test {

using mesh::PolygonSoup;
using mesh::SurfaceMesh;
using mesh::Vec3;

//        3
//       /|\        unit right-handed tet, faces outward:
//      / | \       (0,2,1) bottom z=0, (0,1,3) y=0, (0,3,2) x=0, (1,2,3) slanted
//     0--|--2
//      \ | /
//        1
inline SurfaceMesh tetrahedron(Vec3 shift = Vec3::Zero(), double scale = 1.0) {
  SurfaceMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  for (auto& v : m.vertices) v = v * scale + shift;
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

// Axis-aligned cube [lo, hi]^3 as 12 outward triangles.
inline SurfaceMesh cube(double lo = 0.0, double hi = 1.0) {
  SurfaceMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1 ? hi : lo, i & 2 ? hi : lo, i & 4 ? hi : lo);
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// Concatenates b after a (indices of b shifted).
inline SurfaceMesh join(SurfaceMesh a, const SurfaceMesh& b) {
  const int n = a.num_vertices();
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto f : b.faces) a.faces.push_back({f[0] + n, f[1] + n, f[2] + n});
  return a;
}

inline SurfaceMesh flipped(SurfaceMesh m) {
  for (auto& f : m.faces) std::swap(f[1], f[2]);
  return m;
}

} // namespace curvetet::test

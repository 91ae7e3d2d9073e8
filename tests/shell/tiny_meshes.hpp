#pragma once
// Small closed meshes built in code for the shell tests.
#include "curvetet/mesh/surface_mesh.hpp"

#include <map>
#include <utility>

namespace curvetet::shell::test {

// Regular octahedron, radius 1, outward-oriented (6 vertices, 8 faces).
//            4 (+z)
//          / | \        equator: 0 (+x), 1 (+y), 2 (-x), 3 (-y)
//     2 --- 3,1 --- 0
//          \ | /
//            5 (-z)
inline mesh::SurfaceMesh octahedron() {
  mesh::SurfaceMesh m;
  m.vertices = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 4; ++i) {
    const int a = i, b = (i + 1) % 4;
    m.faces.push_back({a, b, 4});
    m.faces.push_back({b, a, 5});
  }
  return m;
}

// Octahedron subdivided `levels` times and pushed to the unit sphere.
inline mesh::SurfaceMesh sphere(int levels) {
  mesh::SurfaceMesh m = octahedron();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = mid.find({key.first, key.second});
      if (it != mid.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      const int id = m.num_vertices() - 1;
      mid[{key.first, key.second}] = id;
      return id;
    };
    std::vector<mesh::Tri> faces;
    for (auto [a, b, c] : m.faces) {
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      faces.push_back({a, ab, ca});
      faces.push_back({ab, b, bc});
      faces.push_back({ca, bc, c});
      faces.push_back({ab, bc, ca});
    }
    m.faces = faces;
  }
  return m;
}

} // namespace curvetet::shell::test

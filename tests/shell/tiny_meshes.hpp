#pragma once
// Small closed meshes built in code for the shell tests.
#include "curvetet/mesh/surface_mesh.hpp"

#include <cmath>
#include <array>
#include <map>
#include <vector>
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

namespace curvetet::shell::test {

// A closed polyhedron with a singular vertex at the origin. Its star is six
// quarter-plane triangles through the origin (each in a coordinate plane),
// spanning the skew hexagon +x, +y, +z, -y, -x, -z of the unit octahedron;
// four octahedron faces close it. The star's normals include +z and -z:
// no direction sees all faces around the origin.
//
//            +z
//            |  +y        star: (0,+x,+y) (0,+y,+z) (0,+z,-y)
//            | /                (0,-y,-x) (0,-x,-z) (0,-z,+x)
//   -x ------0------ +x   cap:  octahedron faces of octants
//           /|                  (+++) (+-+) (+--) (---)
//        -y  |
//            -z
inline mesh::SurfaceMesh folded_star() {
  mesh::SurfaceMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  auto axis = [](int sign, int dim) { return dim == 0 ? (sign > 0 ? 1 : 4) : dim == 1 ? (sign > 0 ? 2 : 5) : (sign > 0 ? 3 : 6); };
  // Cap faces, counter-clockwise seen from outside the octahedron.
  for (auto [sx, sy, sz] : std::vector<std::array<int, 3>>{{1, 1, 1}, {1, -1, 1}, {1, -1, -1}, {-1, -1, -1}}) {
    const int a = axis(sx, 0), b = axis(sy, 1), c = axis(sz, 2);
    if (sx * sy * sz > 0) m.faces.push_back({a, b, c});
    else m.faces.push_back({a, c, b});
  }
  // Star faces, oriented against the cap face sharing their ring edge.
  const int ring[6] = {1, 2, 3, 5, 4, 6};
  for (int k = 0; k < 6; ++k) {
    const int a = ring[k], b = ring[(k + 1) % 6];
    bool cap_has_ab = false; // a cap face walks a -> b
    for (int f = 0; f < 4; ++f)
      for (int i = 0; i < 3; ++i) cap_has_ab |= m.faces[f][i] == a && m.faces[f][(i + 1) % 3] == b;
    if (cap_has_ab) m.faces.push_back({0, b, a});
    else m.faces.push_back({0, a, b});
  }
  return m;
}

} // namespace curvetet::shell::test

#pragma once
// Small closed surfaces built in code for the volume tests, and offsets made
// by scaling about a centre (valid for star-shaped convex shapes).
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/volume/layered_surface.hpp"

#include <cmath>
#include <map>

namespace curvetet::test {

//   cube [0,1]^3, two outward triangles per side
inline mesh::SurfaceMesh unit_cube() {
  mesh::SurfaceMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

inline mesh::SurfaceMesh octahedron() {
  mesh::SurfaceMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

// Icosphere with `levels` subdivisions, radius 1, centred at 0.
inline mesh::SurfaceMesh icosphere(int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  mesh::SurfaceMesh m;
  m.vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
             {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& v : m.vertices) v.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return mid[key] = m.num_vertices() - 1;
    };
    std::vector<mesh::Tri> next;
    for (auto f : m.faces) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      next.insert(next.end(), {{f[0], a, c}, {f[1], b, a}, {f[2], c, b}, {a, b, c}});
    }
    m.faces = std::move(next);
  }
  return m;
}

// Offsets by scaling about `centre` (inward for s < 1, outward for s > 1).
inline volume::LayeredSurface scaled_offset(const mesh::SurfaceMesh& m, const mesh::Vec3& centre, double s) {
  volume::LayeredSurface l;
  l.surface = m;
  l.side = s < 1 ? volume::OffsetSide::inward : volume::OffsetSide::outward;
  for (const auto& v : m.vertices) l.offset.push_back(centre + s * (v - centre));
  return l;
}

// Exact enclosed volume of a closed outward surface (double sum of signed
// tets from the origin; fine to 1e-12 for these small shapes).
inline double enclosed_volume(const mesh::SurfaceMesh& m) {
  double v = 0;
  for (const auto& f : m.faces)
    v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6.0;
  return v;
}

} // namespace curvetet::test

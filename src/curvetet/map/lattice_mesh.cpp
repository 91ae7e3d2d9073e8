#include "curvetet/map/lattice_mesh.hpp"

#include "curvetet/highorder/node_ordering.hpp"

namespace curvetet::map {

mesh::SurfaceMesh boundary_lattice_mesh(const mesh::BoundaryMap& m) {
  mesh::SurfaceMesh out;
  out.vertices = m.nodes;
  const int P = m.order;
  auto at = [&](const int* tri, int a, int b) { return tri[highorder::triangle_node_index(P, {a, b})]; };
  for (int t = 0; t < m.num_triangles(); ++t) {
    const int* tri = m.triangle(t);
    for (int b = 0; b < P; ++b)
      for (int a = 0; a + b < P; ++a) {
        out.faces.push_back({at(tri, a, b), at(tri, a + 1, b), at(tri, a, b + 1)});
        if (a + b + 1 < P) out.faces.push_back({at(tri, a + 1, b), at(tri, a + 1, b + 1), at(tri, a, b + 1)});
      }
  }
  return out;
}

} // namespace curvetet::map

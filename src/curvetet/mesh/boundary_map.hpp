#pragma once
// The bijective map φ between the input surface and the output boundary
// (DESIGN.md §3.3), as plain data: what `--map OUT.map` writes and
// `curvetet transfer` reads (file layout: docs/map_format.md).
//
// Output side: the boundary of the curved tet mesh as `triangles`, each of
// order P with triangle_nodes(P) entries in internal (Gmsh) triangle order,
// indexing `nodes` (the distinct boundary nodes; node_ids[j] is node j's id
// in the TetMesh / .msh, 0-based). Boundary triangle b is the TetMesh's
// boundary triangle b (same order, same corner order).
//
// A SurfacePoint {face, u, v} is the point with barycentric weights
// (1-u-v, u, v) on the face's corners 0, 1, 2: on an input face that is the
// flat triangle; on a boundary triangle it is the curved Lagrange triangle
// evaluated at reference (u, v) (highorder/element_map.hpp), so a curved
// boundary is handled exactly.
//
// vertex_to_boundary[i] = φ(input vertex i) (a boundary triangle and (u, v));
// node_to_input[j] = φ⁻¹(boundary node j) (an input face and (u, v)).
#include "curvetet/mesh/surface_mesh.hpp"

#include <vector>

namespace curvetet::mesh {

struct SurfacePoint {
  int face = -1;
  double u = 0, v = 0;
};

struct BoundaryMap {
  int order = 1;                         // P of the boundary triangles
  SurfaceMesh input;                     // the input surface (vertices, faces)
  std::vector<Vec3> nodes;               // output boundary nodes
  std::vector<int> node_ids;             // per node: TetMesh node id
  std::vector<int> triangles;            // num_triangles() x triangle_nodes(), into `nodes`
  std::vector<SurfacePoint> vertex_to_boundary; // per input vertex
  std::vector<SurfacePoint> node_to_input;      // per boundary node

  int triangle_nodes() const { return (order + 1) * (order + 2) / 2; }
  int num_triangles() const { return static_cast<int>(triangles.size()) / triangle_nodes(); }
  const int* triangle(int b) const { return triangles.data() + static_cast<std::size_t>(b) * triangle_nodes(); }
};

} // namespace curvetet::mesh

#pragma once
// φ and φ⁻¹ of the finished pipeline as a BoundaryMap (mesh/boundary_map.hpp).
//
// Boundary triangle b of `mesh` is matched to the shell face whose middle
// corners it has (bit-equal positions; its corner order is a rotation of the
// face's). Then
//   input vertex i -> shell.points[i].image = (face f, u, v) re-expressed in
//                     the corner order of f's boundary triangle;
//   boundary node  -> its lattice (u, v) on its face f, then Π⁻¹: the fiber
//                     of (u, v) in prism f meets one of the input faces
//                     f tracks (shell::fiber_hit; the deepest hit wins).
// The output boundary is the middle surface evaluated at the same (u, v) Π
// gives, flat or curved, so nothing here assumes a flat boundary.
#include "curvetet/mesh/boundary_map.hpp"
#include "curvetet/mesh/tet_mesh.hpp"
#include "curvetet/shell/shell.hpp"

namespace curvetet::map {

struct MapBuildStats {
  int nodes = 0, triangles = 0;
  int node_fallbacks = 0;       // nodes whose fiber missed in their first face but hit in a neighbour's
  double min_hit_depth = 0;     // smallest barycentric depth of a Π⁻¹ hit (>= -1e-9)
};

// `mesh` is the pipeline's output for `shell` (pipeline::PipelineResult).
// Throws Error(internal) when a boundary triangle matches no shell face or a
// node's fiber meets no tracked input face (a broken shell invariant).
mesh::BoundaryMap build_boundary_map(const shell::Shell& shell, const mesh::TetMesh& mesh, MapBuildStats* stats = nullptr);

} // namespace curvetet::map

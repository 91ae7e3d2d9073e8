#pragma once
// A conforming flat triangulation of the curved boundary of a TetMesh.
//
// Each boundary triangle of order P is sampled on the uniform lattice with
// s segments per edge (s >= 1) and split into s^2 flat triangles, oriented
// like the curved face. Points on a shared edge are computed once (keyed by
// the edge's global corner ids and the lattice step from its smaller corner)
// and reused by the neighbouring face, and corners are the mesh nodes
// themselves, so the result is a conforming SurfaceMesh whose topology is the
// curved boundary's: a test on it (closed, manifold, self-intersection, exact)
// is an exact test of this piecewise-linear approximation of the curved
// boundary, which converges to the curved surface as s grows.
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace curvetet::check {

struct BoundaryLinearization {
  mesh::SurfaceMesh surface;
  std::vector<int> source_face; // boundary triangle of each flat triangle
  // Per flat triangle: its corners' (u, v) on the source triangle's
  // reference triangle (highorder::triangle_point).
  std::vector<std::array<Eigen::Vector2d, 3>> source_uv;
};

BoundaryLinearization linearize_boundary(const mesh::TetMesh& mesh, int segments_per_edge);

} // namespace curvetet::check

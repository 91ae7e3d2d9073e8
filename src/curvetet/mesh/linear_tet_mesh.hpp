#pragma once
// Plain linear tetrahedral mesh passed between stages (the fill of the
// volume stage; the curved output is mesh::TetMesh, tet_mesh.hpp).
//
// tets[i] = (a, b, c, d) with orient3d(a, b, c, d) > 0 (geometry/predicates.hpp
// convention: d sees a, b, c counter-clockwise). tags[i] names the region the
// tet belongs to (size tets.size() or empty = all 0).
#include "curvetet/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace curvetet::mesh {

struct LinearTetMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 4>> tets;
  std::vector<int> tags;

  int num_vertices() const { return static_cast<int>(vertices.size()); }
  int num_tets() const { return static_cast<int>(tets.size()); }
};

// The same mesh as an order-1 TetMesh (for the MSH/VTU writers and the
// verifier): tet tags kept (0 becomes 1); one named group per tag
// (`names[tag]` if given, else "region<tag>"). No boundary triangles listed.
TetMesh to_order1_mesh(const LinearTetMesh& m, const std::vector<std::string>& names = {});
LinearTetMesh to_linear_mesh(const TetMesh& m); // order-1 input; tags kept

} // namespace curvetet::mesh

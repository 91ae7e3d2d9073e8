#pragma once
// Plain linear tetrahedral mesh passed between stages.
//
// tets[i] = (a, b, c, d) with orient3d(a, b, c, d) > 0 (geometry/predicates.hpp
// convention: d sees a, b, c counter-clockwise). tags[i] names the region the
// tet belongs to (size tets.size() or empty = all 0).
#include <Eigen/Core>

#include <array>
#include <vector>

namespace curvetet::mesh {

struct TetMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 4>> tets;
  std::vector<int> tags;

  int num_vertices() const { return static_cast<int>(vertices.size()); }
  int num_tets() const { return static_cast<int>(tets.size()); }
};

} // namespace curvetet::mesh

#pragma once
// Feature edges by dihedral angle (`--feature-angle DEG`): an interior edge
// is a feature when the angle between its two faces' normals exceeds DEG
// (0 = coplanar, 180 = folded flat). Only edges with exactly two faces are
// considered. Result sorted, [0] < [1].
#include "curvetet/mesh/edge_topology.hpp"
#include "curvetet/mesh/surface_mesh.hpp"

#include <array>
#include <vector>

namespace curvetet::features {

std::vector<std::array<int, 2>> detect_feature_edges(const mesh::SurfaceMesh& mesh, const mesh::EdgeTopology& topo,
                                                     double angle_degrees);

} // namespace curvetet::features

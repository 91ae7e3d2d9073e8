#pragma once
// The boundary of a BoundaryMap as a flat triangle mesh over all its nodes:
// each order-P triangle becomes its P² lattice sub-triangles (same
// orientation). For viewers and PLY output; the map itself stays curved.
#include "curvetet/mesh/boundary_map.hpp"

namespace curvetet::map {

mesh::SurfaceMesh boundary_lattice_mesh(const mesh::BoundaryMap& map);

} // namespace curvetet::map

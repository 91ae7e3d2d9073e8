#pragma once
// Unsigned distance from query points to a triangle mesh (CGAL AABB tree
// inside the .cpp; plain double: a MEASUREMENT for reports, never a
// guarantee). Queries run in parallel; results do not depend on threads.
#include "curvetet/mesh/surface_mesh.hpp"

#include <vector>

namespace curvetet::check {

// distances[i] = min over faces of |queries[i] - face|. Empty mesh: +inf.
std::vector<double> distances_to_surface(const mesh::SurfaceMesh& surface, const std::vector<mesh::Vec3>& queries);

} // namespace curvetet::check

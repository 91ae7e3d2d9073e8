#pragma once
// Unsigned distance from query points to a triangle mesh (CGAL AABB tree
// inside the .cpp; plain double: a MEASUREMENT for reports, never a
// guarantee). Queries run in parallel; results do not depend on threads.
#include "curvetet/mesh/surface_mesh.hpp"

#include <vector>

namespace curvetet::check {

// distances[i] = min over faces of |queries[i] - face|. Empty mesh: +inf.
std::vector<double> distances_to_surface(const mesh::SurfaceMesh& surface, const std::vector<mesh::Vec3>& queries);

struct ClosestPoint {
  int face = -1; // -1: empty mesh
  mesh::Vec3 point = mesh::Vec3::Zero();
};
// The closest point of the surface to each query, and its face.
std::vector<ClosestPoint> closest_points(const mesh::SurfaceMesh& surface, const std::vector<mesh::Vec3>& queries);

} // namespace curvetet::check

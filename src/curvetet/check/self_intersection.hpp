#pragma once
// Exact self-intersection test of a triangle mesh (any topology).
//
// Two faces intersect improperly by geometry::triangles_intersect_improperly
// (shared vertex ids decide which corners are shared).
// Degenerate (zero-area) faces are skipped: they are reported on their own.
// Candidates come from bounding-box overlap; every decision is exact.
#include "curvetet/mesh/surface_mesh.hpp"

#include <utility>
#include <vector>

namespace curvetet::check {

// Sorted pairs (f, g), f < g, of faces that intersect improperly.
// skip[f] = true excludes face f (size num_faces or empty).
std::vector<std::pair<int, int>> self_intersections(const mesh::SurfaceMesh& m, const std::vector<bool>& skip = {});

// Whether two faces of `m` intersect improperly (the rule above).
bool faces_intersect(const mesh::SurfaceMesh& m, int f, int g);

} // namespace curvetet::check

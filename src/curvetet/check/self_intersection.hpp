#pragma once
// Exact self-intersection test of a triangle mesh (any topology).
//
// Two faces intersect improperly when
//  - they share no vertex and meet at all;
//  - they share exactly one vertex v and meet anywhere else: decided as
//    "the edge opposite v in one meets the other face" (either way round),
//    which is exact and complete because both faces are convex and contain v;
//  - they share an edge and are coplanar with their third corners on the
//    same side of it (they overlap: a fold of zero dihedral angle).
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

#pragma once
// INTERNAL to volume/*.cpp. Recovery of surface triangles that a
// tetrahedralization (the Delaunay one of the surface's vertices) lacks, by
// flips only (no Steiner point), for fill_direct() (direct_fill.hpp):
//  - a missing edge uv: removal of an edge de whose ring holds u and v (the
//    ring re-tetrahedralized from a polygon triangulation with diagonal uv),
//    or the 2-3 flip of a face between u and v, or a walk of 2-3 flips along
//    uv, each kept only if it shortens the walk;
//  - then the triangle: removal of an edge de whose ring holds its corners.
// Every new tet is checked positive with exact orient3d, and no surface edge
// is ever removed, so the result is a valid tetrahedralization of the same
// points that keeps every surface triangle it had.
#include "curvetet/volume/background.hpp"

namespace curvetet::volume {

// Returns bg (neighbours recomputed) after trying to recover the triangles
// surface[missing[i]]; sweeps again while a sweep recovers a fifth of those
// left.
BackgroundMesh recover_triangles(const BackgroundMesh& bg, const std::vector<mesh::Tri>& surface,
                                 const std::vector<int>& missing);

} // namespace curvetet::volume

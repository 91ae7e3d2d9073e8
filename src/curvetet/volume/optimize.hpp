#pragma once
// INTERNAL to volume/*.cpp. Step 5 of paper §4.3 (TetWild §3.2 with the
// surface frozen): rounding of rational vertices and AMIPS optimization.
//
// Every operation is a transaction: build the new star, check every new tet
// positive with exact orient3d (rational where a vertex is not yet rounded),
// commit or drop. Frozen vertices never move and are never collapsed away, so
// the boundary faces never change (a collapse or flip never touches a
// boundary face: see the checks in exact_optimizer_collapse.cpp and
// exact_optimizer_flips.cpp).
#include "curvetet/mesh/linear_tet_mesh.hpp"
#include "curvetet/volume/exact_mesh.hpp"
#include "curvetet/volume/fill.hpp"

namespace curvetet::volume::exact {

// Consumes the exact mesh; returns a double mesh (unused vertices dropped;
// vertices [0, num_keep) keep their ids). Throws Error(internal) if a vertex
// cannot be rounded.
mesh::LinearTetMesh round_and_optimize(ExactTetMesh&& m, int num_keep, const FillOptions& options, FillStats& stats);

} // namespace curvetet::volume::exact

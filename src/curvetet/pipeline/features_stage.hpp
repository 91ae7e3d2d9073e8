#pragma once
// Features through the pipeline (paper §5).
//
// refine_for_features: the surface the shell is built on: every triangle
// with 2+ feature edges of `g` refined 1-to-3 (features/refine.hpp; input
// vertex ids kept, so `g` stays valid on it).
//
// add_feature_lines: the output's feature curves: every coarse feature edge of the
// shell becomes an order-P line element of the output mesh, sharing the
// nodes of the boundary triangle edge it lies on (physical group "features",
// mesh::kFeatureTag). The boundary of the assembled mesh is the shell's
// middle surface, whose corner nodes are the middle vertices bit for bit.
#include "curvetet/features/chains.hpp"
#include "curvetet/mesh/tet_mesh.hpp"
#include "curvetet/shell/shell.hpp"

namespace curvetet::pipeline {

mesh::SurfaceMesh refine_for_features(const mesh::SurfaceMesh& input, const features::FeatureGraph& g);

// Appends the lines to mesh.lines / line_tags and the "features" group.
// Returns the number of lines added; throws Error(internal) if a feature
// edge of the shell is not an edge of a boundary triangle.
int add_feature_lines(mesh::TetMesh& mesh, const shell::Shell& s);

} // namespace curvetet::pipeline

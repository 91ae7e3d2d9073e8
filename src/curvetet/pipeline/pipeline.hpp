#pragma once
// The whole pipeline (DESIGN.md §1) as one function from a checked input
// surface to a curved order-P tet mesh, re-verified:
//   shell::build_shell -> shell::coarsen_shell (under epsilon) -> middle
//   nodes of degree P-1 (linear until the curved fit lands) -> fill inside the bottom
//   surface (volume::fill_layered on the shell's one-sided extrusion) ->
//   volume::assemble_curved_mesh -> check::verify_tet_mesh.
// Each stage is timed into the report. Stages that later issues add
// (coarsening, curved fit, curved optimization) slot in between without
// changing this interface.
#include "curvetet/check/verify_tet_mesh.hpp"
#include "curvetet/core/report.hpp"
#include "curvetet/features/chains.hpp"
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/mesh/tet_mesh.hpp"
#include "curvetet/shell/build.hpp"

#include <optional>

namespace curvetet::pipeline {

struct PipelineOptions {
  int order = 4;                       // P: output tets of order P, middle of degree P-1
  double epsilon = 0.01;               // distance bound, x input bbox diagonal
  std::optional<double> epsilon_abs;   // absolute distance bound (overrides epsilon)
  shell::ShellOptions shell;
  bool coarsen = true;
  double fill_offset = 0.01;           // inward offset of the bottom surface, x its bbox diagonal
};

struct PipelineResult {
  mesh::TetMesh mesh;
  check::TetMeshVerification verification;
  shell::Shell shell; // the final shell (its map sends input points to the boundary)
};

// `input` must satisfy check::preconditions. With `features` (grouped on
// `input`; paper §5) the shell is built on the 1-to-3 refined input, keeps
// every corner and chain through coarsening (feature_invariant.hpp), and
// the output mesh carries the coarse feature curves as order-P lines in
// the physical group "features". Throws Error(internal) when a
// stage's own guarantee fails (a bug); the verification's verdict is in the
// result for the caller to act on.
PipelineResult run_pipeline(const mesh::SurfaceMesh& input, const PipelineOptions& options, Report& report,
                            const features::FeatureGraph* features = nullptr);

} // namespace curvetet::pipeline

#pragma once
// The whole pipeline (DESIGN.md §1) as one function from a checked input
// surface to a curved order-P tet mesh, re-verified:
//   shell::build_shell -> shell::coarsen_shell (under epsilon, fitting a
//   curved middle of degree P-1 in every operation) -> the interior filled on
//   the middle surface (volume::assemble_retracted: corners whose tets do
//   not certify retracted to the bottom surface, round after round) or, with
//   --fill all or --slab-layer, inside the bottom surface
//   (volume::fill_layered) plus every slab (volume::assemble_curved_mesh) ->
//   volume::remesh_curved (certified collapses, flips, splits and smoothing)
//   -> check::verify_tet_mesh.
// With a curved middle the assembled tets are certified before the
// optimization; if any is not positive (seen on nefertiti, see run_pipeline),
// everything runs again with a flat middle (report "curved_middle_fallback").
// When the output's worst elements miss the quality targets, everything runs
// again with the coarsening's thickness rule (ratio 3, then 2 when that was
// kept and meets one target only), kept if it meets them or is better in both
// measures (report "thin_part_retry"; PipelineOptions).
// Each stage is timed into the report. Stages that later issues add
// (coarsening, curved fit, curved optimization) slot in between without
// changing this interface.
#include "curvetet/check/verify_tet_mesh.hpp"
#include "curvetet/core/report.hpp"
#include "curvetet/features/chains.hpp"
#include "curvetet/features/feature_input.hpp"
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/mesh/tet_mesh.hpp"
#include "curvetet/shell/build.hpp"
#include "curvetet/volume/curved_remesh.hpp"

#include <limits>
#include <optional>

namespace curvetet::pipeline {

// Which regions get tets: the solid inside the middle surface, or also the
// space between it and a box around it (flows around an obstacle; the
// exterior tets are tagged "exterior", the box faces "box").
enum class FillRegion { interior, all };

struct PipelineOptions {
  int order = 4;                       // P: output tets of order P, middle of degree P-1
  double epsilon = 0.01;               // distance bound, x input bbox diagonal
  std::optional<double> epsilon_abs;   // absolute distance bound (overrides epsilon)
  shell::ShellOptions shell;
  bool coarsen = true;
  bool curved_middle = true;           // fit a degree P-1 middle while coarsening (else flat)
  double fill_offset = 0.01;           // inward offset of the bottom surface, x its bbox diagonal
  FillRegion fill = FillRegion::interior;
  bool slab_layer = false;             // interior: always the paper's assembly (fill inside B + bottom slabs)
  double box_margin = 0.1;             // --fill all: the box grows the top's bbox by this x diagonal per side
  // Coarsening: a new boundary triangle's longest edge may reach this x the
  // solid's thickness under it (shell/local_thickness.hpp; 3-4 keep thin
  // walls and tubes from flat tets, at the price of more tets); inf: no rule.
  double thickness_ratio = std::numeric_limits<double>::infinity();
  // Without a thickness_ratio: when the verified output's max AMIPS or min
  // scaled Jacobian (the validator's convention) misses these targets, the
  // stages run again with the thickness rule (ratio 3), whose output is kept
  // when it meets them or is better in both; when kept and meeting one
  // target only, again with ratio 2 (report "thin_part_retry").
  bool thin_part_retry = true;
  double target_max_amips = 30;
  double target_min_scaled_jacobian = 0.02;
  bool optimize = true;                // curved optimization after the assembly
  volume::CurvedRemeshOptions optimization;
  // Points of the input (face, barycentric; features file "points") where
  // input -> boundary is enforced besides the input vertices.
  features::ConstraintPoints constraint_points;
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

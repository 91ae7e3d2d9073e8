#pragma once
// Construction of a valid thin shell around an input surface (DESIGN.md §3.1).
//
//  1. Extrusion directions (extrusion.hpp); singular vertices detected.
//  2. Isolation: every edge joining two singular vertices is split at its
//     midpoint (new vertex appended; each split face becomes two faces that
//     both track the original input face). Repeated while needed (at most a
//     few passes; a fold no split can separate throws Error(internal) naming
//     the vertices).
//  3. Initial shell: middle = (split) input, pillars along the directions with
//     a tiny length halved per vertex until invariants 1-3 hold; then
//     thickening rounds toward the target (layer_growth.hpp). Both sides grow
//     by the same length: top = middle + l d, bottom = middle - l d.
//  4. The map: every input vertex i is points[i], mapped to a middle face
//     incident to it with (u, v) its corner (Π is the identity there).
// Preconditions: those of check::preconditions (closed, manifold, oriented
// outward, no degenerate face, no self-intersection).
#include "curvetet/shell/extrusion.hpp"
#include "curvetet/shell/shell.hpp"

namespace curvetet::shell {

struct ShellOptions {
  ExtrusionOptions extrusion;
  bool debug_invariants = false; // global check after every stage (throws)
};

struct ShellBuildStats {
  int input_vertices = 0, input_faces = 0;
  int singular_vertices = 0; // after isolation
  int split_edges = 0;
  int initial_halvings = 0, rounds = 0;
  long long reverts = 0;
  // Per non-singular vertex: length of one side's pillar; thickness = |T - B|.
  double min_pillar = 0, max_pillar = 0, mean_pillar = 0;
  double min_thickness = 0, max_thickness = 0, mean_thickness = 0;
  double target_pillar = 0;
  int vertices_at_target = 0;
  // seconds_isolation includes the extrusion directions.
  double seconds_isolation = 0, seconds_initial = 0, seconds_thickening = 0,
         seconds_map = 0, seconds_total = 0;
};

struct ShellBuild {
  Shell shell;
  ShellBuildStats stats;
};

ShellBuild build_shell(const mesh::SurfaceMesh& input, const ShellOptions& options = {});

// Appends constraint points (the paper's set P beyond the input vertices:
// points where input -> boundary is enforced by the Distance invariant) to
// s.points. Point i lies at `positions[i]` on the input triangle whose
// vertex ids are `near[i]` (ids of s.input's vertices; the triangle itself
// may have been refined into faces around those vertices): it is placed on
// the face of s.input beside those vertices that holds it best, and mapped
// by Π. Call on a built shell, before coarsening. Throws Error(internal) if
// no prism holds a point.
void add_constraint_points(Shell& s, const std::vector<Vec3>& positions, const std::vector<Tri>& near);

// Splits every edge between two singular vertices of `m` (step 2 above) and
// returns, per face of the result, the face of `m` it lies in. Vertices of m
// keep their ids; new ones are appended. Exposed for tests.
struct IsolatedMesh {
  mesh::SurfaceMesh mesh;
  std::vector<int> origin_face;
  std::vector<DirectionResult> directions;
  int split_edges = 0;
};
IsolatedMesh isolate_singularities(const mesh::SurfaceMesh& m, double singular_dot);

} // namespace curvetet::shell

#pragma once
// Internal: grows the pillars of a shell whose middle and tracked faces are
// set, keeping invariants 1-3 (shared by build_shell and extrude_one_sided).
//
// Vertex v sits at top = middle + len*d (if grow_top, else middle) and
// bottom = middle - len*d (if grow_bottom, else middle); d is unit or zero
// (singular: the pillar stays pinched).
//  1. Initial layer: every len = initial; the vertices of failing prisms (or
//     of intersecting caps) are halved until everything holds.
//  2. Rounds: every unfinished vertex proposes len * factor (capped at the
//     target and at neighbour_ratio x the thinnest neighbour); failing prisms / cap pairs touched by a proposal revert their
//     proposing vertices (re-checking what the reverts touched) until the
//     shell is valid again. A reverted vertex takes the square root of its
//     factor and stops when it drops below min_factor; a vertex reaching the
//     target stops.
// Only the prisms around changed vertices are re-checked (and their caps
// against all caps). Deterministic for any thread count.
#include "curvetet/shell/extrusion.hpp"
#include "curvetet/shell/shell.hpp"

#include <functional>
#include <string_view>
#include <vector>

namespace curvetet::shell {

struct LayerGrowthSpec {
  std::vector<Vec3> direction; // per vertex, unit or zero
  bool grow_bottom = true, grow_top = true;
  double initial = 0, target = 0; // absolute lengths
  int max_rounds = 30;
  double growth_factor = 4;   // first proposal: len * 4; square-rooted on each failure
  double neighbour_ratio = 2; // proposals capped at this x the thinnest neighbour
  double min_factor = 1.2;    // a vertex whose factor falls below this stops
  // Called after the initial layer and after the rounds (e.g. the global
  // --debug-invariants check); may throw.
  std::function<void(const Shell&, std::string_view stage)> after_stage;
  // Polled before every check pass and between batches of its exact cap
  // tests (possibly from worker threads); when it returns true, grow_layer throws
  // Stopped (extrusion.hpp; the caller no longer wants the layer).
  std::function<bool()> stop_requested;
};

// A shell over `surface` with no layer yet: bottom, middle and top are its
// vertices, each prism tracks its own face, and no pillar is pinched.
Shell flat_shell(const mesh::SurfaceMesh& surface);

struct LayerGrowthStats {
  int initial_halvings = 0; // halving passes of the initial layer
  int rounds = 0;
  long long reverts = 0;    // vertex growths undone
  double seconds_initial = 0, seconds_rounds = 0;
};

// Fills s.bottom / s.top; returns the per-vertex length in `length`.
LayerGrowthStats grow_layer(Shell& s, const LayerGrowthSpec& spec, std::vector<double>& length);

} // namespace curvetet::shell

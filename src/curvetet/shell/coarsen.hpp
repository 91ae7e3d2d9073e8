#pragma once
// Coarsening of a valid shell by local operations under a distance bound
// (DESIGN.md §3.2; paper §4, App. B). Linear middle surface by default; the
// curved fit plugs in through MiddleFit (middle_fit.hpp).
//
// Rounds of passes: collapse (shortest middle edge first), flip (valence
// gain), smooth (every vertex once: pan / rotate / zoom), split (edges longer
// than split_factor x the mean edge, longest first); with a curved middle
// also refit (every vertex star's middle nodes fitted again, after smooth).
// A round whose collapse pass accepts nothing or removes less than
// min_round_gain of the faces is the last, and skips its split (which would
// only leave faces behind); so is round max_rounds.
//
// Every operation is a transaction (operations.hpp -> star_invariants.hpp ->
// ShellEditor::commit). The scheduler batches non-overlapping stars (no
// shared vertex) in priority order, checks a batch in parallel (oneTBB) and
// commits it sequentially in that order, so the result does not depend on
// the thread count.
//
// Guarantees after coarsen_shell (on a valid input shell): invariants 1-3 of
// DESIGN.md §2 hold (exact); every constraint point p satisfies
// ||p - middle(Π(p))|| < epsilon; s.points[i].image is Π(p_i); tracked sets
// contain every input face meeting the prism. The shell has no dead entries.
#include "curvetet/shell/middle_fit.hpp"
#include "curvetet/shell/shell.hpp"
#include "curvetet/shell/star.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace curvetet::shell {

struct CoarsenOptions {
  double epsilon = 0.01;       // distance bound, relative to the input bbox diagonal
  double epsilon_abs = 0;      // absolute override when > 0
  double quality_bound = 30;   // MIPS of new middle triangles above this: no worse than an old one across an edge
  // AMIPS (highorder/quality.hpp: 3 for the regular tet) of the tets of new
  // lower slabs may reach max(old, this): in thin regions the shell is thin,
  // and long faces there make flat output tets.
  double slab_quality_bound = std::numeric_limits<double>::infinity();
  // 2D MIPS of new fitted (curved) middle patches, on their order-2k
  // lattice, may reach max(old, this): a patch distorted far beyond its
  // flat triangle caps the quality of every tet on it.
  double curved_quality_bound = std::numeric_limits<double>::infinity();
  // New middle triangles' longest edge over the solid's thickness under
  // their thinnest corner (local_thickness.hpp) may reach max(old, this):
  // a face much longer than the solid is thick leaves only flat tets.
  double thickness_ratio = std::numeric_limits<double>::infinity();
  double split_factor = 3.0;   // split edges longer than this x mean edge length (0: never)
  double target_pillar = 0.02; // zoom target, relative to the diagonal
  double singular_dot = 1e-3;  // as ExtrusionOptions::singular_dot
  int max_rounds = 10;
  double min_round_gain = 0.01; // stop when a round removes fewer faces than this fraction
  bool debug_invariants = false; // global check (invariants 1-3, distance, map) after every pass
  // Skip collapses and smooths whose star is unchanged since a local
  // invariant rejected them (rejection_memo.hpp); same result either way.
  bool remember_rejections = true;
  // With a curved fit: coarsen with a flat middle first (fast, and where a
  // curved patch gains nothing, e.g. flat CAD facets, the greedy order is
  // not disturbed by fits and certificates), then go on coarsening that
  // shell with the curved middle, every operation fitting and certifying.
  // bunny: 372 faces (curved from the start: 396; flat only: 512).
  bool flat_first = true;
};

struct PassStats {
  OpKind op = OpKind::collapse;
  int round = 0;
  long long tried = 0, accepted = 0, batches = 0;
  long long remembered = 0; // entries rejected unchanged since an earlier pass (rejection_memo.hpp)
  std::array<long long, kRejectionCount> rejected{};
  int faces_before = 0, faces_after = 0;
  double seconds = 0;
  double check_seconds = 0; // of which in the parallel check phase (the rest is serial)
  // CPU seconds of the check phase: building candidates, and each
  // invariant (by its rejection reason).
  double proposal_seconds = 0;
  std::array<double, kRejectionCount> invariant_seconds{};
};

// Rejected candidates per reason, keyed by to_string(Rejection) (the
// reports' form): of one pass, or summed over a whole coarsening.
nlohmann::json rejections_json(const PassStats& pass);
nlohmann::json rejections_json(const std::vector<PassStats>& passes);

// CPU seconds summed over the passes: "proposals" (building candidates) and
// one entry per invariant, keyed by its rejection reason.
nlohmann::json check_seconds_json(const std::vector<PassStats>& passes);

struct CoarsenStats {
  int faces_before = 0, faces_after = 0;
  int vertices_before = 0, vertices_after = 0;
  double epsilon = 0;        // absolute
  double max_distance = 0;   // over all constraint points at the end
  double max_surface_distance = 0; // bound over the middle surface at the end (surface_distance.hpp)
  int rounds = 0;
  double seconds = 0;
  std::vector<PassStats> passes;
};

// Coarsens s in place. `fit` defaults to the linear middle. A curved fit of
// degree k starts from s's middle nodes when they have degree k, else from
// the flat triangles (set_flat_middle); s ends with its fitted nodes.
CoarsenStats coarsen_shell(Shell& s, const CoarsenOptions& options = {}, const MiddleFit* fit = nullptr);

// Whole-map verification (tests, --debug-invariants, report).
struct MapCheck {
  double max_distance = 0;   // max ||p - middle(image(p))|| over s.points
  int worst_point = -1;
  int points_outside = 0;    // images not inside their prism (Π(p) recomputed differs)
  // Bijectivity, exact: prisms whose tracked faces' images do not tile the
  // middle triangle (sum != 1) or have a negative piece.
  int prisms_not_tiled = 0, prisms_folded = 0;
  double max_area_error = 0; // nearest double to the largest |sum of image areas - 1|
  double min_piece_area = 0; // nearest double to the smallest signed image piece
  int worst_prism = -1;
  bool bijective() const { return prisms_not_tiled == 0 && prisms_folded == 0; }
};
// With bijectivity = false only the distances and containment (the exact
// tiling costs rational arithmetic per tracked face).
MapCheck check_map(const Shell& s, bool bijectivity = true);

} // namespace curvetet::shell

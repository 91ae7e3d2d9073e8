#pragma once
// Curved optimization with topology changes (paper §4.3, end; DESIGN.md §9):
// on the assembled order-P mesh, edge collapses, 2-3 / 3-2 / 4-4 flips and
// edge removals (volume/edit/operations.hpp) and the smoothing of
// curved_optimize.hpp, every new tet certified positive by the Bernstein
// certificate before it is committed, the boundary (the curved middle
// surface), its nodes and the feature curves never changed.
//
// Schedule, per round (quality first, then coarseness):
//  1. quality: the tets whose max AMIPS exceeds target_amips, worst first;
//     for each, every operation on its edges and faces is tried and the one
//     whose new tets have the lowest max AMIPS is kept, if that is below the
//     old star's max AMIPS; where none does and the tet is above
//     split_amips (an ear, with two boundary faces: above
//     ear_split_amips), the same for the splits of its edges;
//  2. coarsening: each free vertex, those with the shortest edge first,
//     collapses onto its best neighbour if the new tets stay under
//     collapse_amips (or under the old star's max AMIPS, when higher);
//  3. coarsening by 3-2 flips: each interior edge with three tets becomes a
//     face (one tet fewer) if the two new tets stay under target_amips
//     (or under the old star's max AMIPS, when higher);
//  4. the quality pass again, for the tets above collapse_amips;
//  5. smoothing (optimize_curved: steps tried on the convention's order-2P
//     lattice, accepted on every sample).
// After the rounds, every free node moves at once (descend_curved: tets
// sharing curved nodes that no single move improves).
// No operation takes a tet below min(min_scaled_jacobian, the old star's
// min scaled Jacobian). Rounds stop when one runs fewer than min_operations
// (x tets) operations, or lowers the max AMIPS by less than
// smoothing.min_gain while tets above collapse_amips are left (below it, the
// rounds go on for coarseness alone). Operations run one at a time;
// the previews of one choice's candidates run in parallel, each on a replica
// of the editor that has replayed every committed operation, so the result
// does not depend on the thread count.
// AMIPS in the validator's convention (highorder/quality.hpp).
#include "curvetet/mesh/tet_mesh.hpp"
#include "curvetet/volume/curved_descent.hpp"
#include "curvetet/volume/curved_optimize.hpp"
#include "curvetet/volume/edit/invariants.hpp"

#include <nlohmann/json.hpp>

namespace curvetet::volume {

struct CurvedRemeshOptions {
  int rounds = 3;
  double min_operations = 0.02;      // a round with fewer operations (x tets) is the last
  double target_amips = 15;          // the quality pass visits tets above this...
  int max_quality_visits = 4096;     // ...the worst this many per round at most
  double collapse_amips = 30;        // a coarsening collapse may create tets up to this
  double split_amips = 100;          // the quality pass splits edges of tets above this only...
  double ear_split_amips = 30;       // ...or of tets with two boundary faces (ears) above this
  double min_scaled_jacobian = 0.05; // floor (see above)
  bool collapse = true, flip = true, split = true, smooth = true, descend = true;
  CurvedOptimizeOptions smoothing = [] {
    CurvedOptimizeOptions o;
    o.bad_fraction = 0.1; // the topology passes handle the bulk; smoothing polishes the worst
    // The descent raises every low scaled Jacobian at once; sweeping each
    // tet below the floor (a third of them on the scans) cost most of the
    // smoothing's time for no better result.
    o.raise_scaled_jacobian_below = 0.02;
    // The joint descent after the rounds does the long smoothing; passes
    // 6-10 of a round gained about 1 % each (docs/usable_elements.md,
    // session 30).
    o.passes = 5;
    return o;
  }();
  CurvedDescentOptions descent;
};

struct CurvedRemeshStats {
  int tets_before = 0, tets_after = 0;
  double max_amips_before = 0, mean_amips_before = 0, min_scaled_jacobian_before = 0;
  double max_amips_after = 0, mean_amips_after = 0, min_scaled_jacobian_after = 0;
  long collapses = 0, flips_2_3 = 0, flips_3_2 = 0, flips_4_4 = 0, edge_removals = 0, splits = 0; // accepted
  edit::RejectCounts rejected{};
  int vertex_moves = 0, node_moves = 0; // smoothing
  int rounds = 0;
  CurvedDescentStats descent;
  double seconds = 0;
  nlohmann::json json() const;
};

CurvedRemeshStats remesh_curved(mesh::TetMesh& mesh, const CurvedRemeshOptions& options = {});

} // namespace curvetet::volume

#pragma once
// Curved optimization of the assembled mesh (paper §4.3, end; DESIGN.md §1
// volume::optimize_curved): smoothing that lowers the max AMIPS of the
// order-P tets and raises their min scaled Jacobian (highorder/quality.hpp's
// convention: both over the order-2P and degree-3(P-1) lattices with their
// corners, as validate.py samples; the regular tet's AMIPS is 3) while the
// boundary stays exactly where it is.
//
// Two local moves, each a transaction on the tets it touches:
//  - vertex move: a corner vertex v not on any listed boundary triangle moves
//    by d, and every node of its star moves by lambda_v(node) d, lambda_v the
//    node's barycentric weight on v (1 at v, 0 on the faces opposite v), so
//    the star's straight parts stay straight and nodes away from v stay put;
//  - node move: one high-order node (edge, face or interior) not on a listed
//    boundary triangle moves by d; tried only when the worst tet it touches
//    is curved (bending a straight tet raises its max AMIPS).
// Each pass sweeps the tets of high max AMIPS, then those of low min scaled
// Jacobian. d is the descent direction of the sweep's measure at its worst
// point among the touched tets near the worst (AmipsFrames' gradients),
// tried with halving steps from a quarter of the longest touched edge; for a vertex move where none of those steps
// passes, the best of the 26 compass directions at the same steps. Steps are
// tried on the order-2P lattice; a move is kept only if it improves the goal
// without hurting the other measure (see CurvedOptimizeOptions) at every
// sample of the convention AND highorder::certify_tet says `positive` for
// every touched tet (undecided = rejected); otherwise the nodes are restored
// bit for bit. Nodes of listed boundary triangles (the middle surface, and
// with an exterior the box) and of every tet face used once never move, so
// the boundary and the map onto it are unchanged. Precondition: every tet
// certified positive (the assembly's verification); then so is the result.
// Deterministic for any thread count: moves are tried in batches of disjoint
// stars, built in order from the tets visited worst first (ties by index).
#include "curvetet/highorder/quality.hpp"
#include "curvetet/mesh/tet_mesh.hpp"

#include <cstddef>
#include <vector>

namespace curvetet::volume {

struct CurvedOptimizeOptions {
  int passes = 10;              // sweeps over the bad tets (stops early when one gains little)
  double min_gain = 0.01;       // a pass that lowers the max AMIPS and raises the min scaled Jacobian by less
                                // than this fraction is the last
  double bad_fraction = 0.25;   // a sweep visits tets whose max AMIPS >= this quantile from the top...
  std::size_t max_bad_tets = 8192; // ...the worst this many at most (both goals: a big mesh's sweep stays bounded)...
  double min_amips = 12.0;      // ...and above this value (regular tet: 3)
  double min_scaled_jacobian = 0.05; // no move takes a tet below this min scaled Jacobian (or below its own
                                     // value when already lower)...
  double raise_scaled_jacobian_below = 0.05; // ...and a sweep raises the tets below this one
  int line_search_steps = 6;    // step halvings below the touched tets' shortest edge (steps start at the longest)
  std::size_t frame_cache_bytes = std::size_t(1) << 30; // memory for cached per-tet frames (speed only)
  bool move_vertices = true;
  bool move_nodes = true;
  // Fill the stats' *_before / *_after figures (a whole-mesh quality pass
  // each); a caller that measures the mesh itself turns this off.
  bool measure = true;
};

struct CurvedOptimizeStats {
  double max_amips_before = 0, mean_amips_before = 0, min_scaled_jacobian_before = 0;
  double max_amips_after = 0, mean_amips_after = 0, min_scaled_jacobian_after = 0;
  int vertex_moves = 0, node_moves = 0;     // accepted
  int scaled_jacobian_moves = 0;            // of which raised a min scaled Jacobian
  int rejected_quality = 0;                 // no step lowered the max AMIPS
  int rejected_certificate = 0;             // lower AMIPS but a tet not certified positive
  int passes = 0;
};

CurvedOptimizeStats optimize_curved(mesh::TetMesh& mesh, const CurvedOptimizeOptions& options = {});

// Max AMIPS, mean AMIPS (plain mean of the tets' means) and min scaled
// Jacobian of a whole mesh, in highorder/quality.hpp's convention.
struct MeshQuality {
  double max_amips = 0, mean_amips = 0, min_scaled_jacobian = 0;
};
MeshQuality mesh_quality(const mesh::TetMesh& mesh);
// The same in two steps: each tet's quality, then the whole mesh's (the
// same figures, bit for bit), for callers that keep the former.
std::vector<highorder::TetQuality> tet_qualities(const mesh::TetMesh& mesh);
MeshQuality summarize(const std::vector<highorder::TetQuality>& tets);

} // namespace curvetet::volume

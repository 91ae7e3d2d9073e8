#pragma once
// Joint smoothing of an order-P mesh (DESIGN.md §9, after the local
// operations of curved_remesh.hpp): every free node moves at once.
//
// The local moves (curved_optimize.hpp) change one vertex or one node at a
// time. Tets under a curved boundary face share their edge and face nodes,
// and where two of them pull a shared node opposite ways no single move
// lowers their worst, though moving the nodes together does (bunny at
// P = 4: 37.2 to 26.5).
//
// Free: the nodes of the tets whose max AMIPS is at least active_ratio x
// the worst, or whose min scaled Jacobian is at most 1 / active_ratio x the
// worst, and of `rings` layers of tets around them (the others weigh at most
// active_ratio^p in E), except the nodes on a listed boundary triangle or a
// hull face (a face of one tet): the boundary, its curved nodes and the
// feature curves stay bit for bit.
// Energy: E = sum over tets and over the order-2P lattice points of the
// quality convention (highorder/amips_frames.hpp) of (AMIPS / A0)^p plus,
// for the frames along the four corners' edges there, (J0 / sJ)^p: A0 the
// input's max AMIPS and J0 its min scaled Jacobian over the tets with a
// free node. A point with det J <= 0 makes E infinite, so the line searches
// stay where every point is positive; a large p makes E follow the worst
// tets. The terms of a tet's points are taken a block of points at a time
// (descent_terms.hpp); the tets whose terms made together less than
// gradient_share of E at the last evaluation add their terms to E but
// nothing to the gradient (they are most of the moved tets).
// Method: L-BFGS with a backtracking (Armijo) line search, its initial
// inverse Hessian the diagonal of the least h^2 over a node's tets, h a
// tet's size (E is scale-free: its curvature in a node goes as 1 / h^2,
// so one step length cannot suit small and large tets at once). The
// result is the iterate of least worst term, max over points of AMIPS / A0
// and J0 / sJ (E's limit as p grows: E can fall while the worst rises for a
// few steps). Stops after max_iterations, when E falls by less than
// min_decrease over `window` iterations, or when the least worst falls by
// less than min_worst_decrease over worst_window iterations (it falls in
// bursts, often hundreds of iterations in: fertility's halves by 400), or
// over its first first_window iterations (where the least worst falls
// late, it has fallen by 5 % or more by then; where it has not fallen by
// 1 %, it barely moves after: docs/performance.md).
// Every checkpoint_iterations the least-worst iterate is checked as below;
// where it fails (a tet inverted between the samples), the latest earlier
// least-worst iterate that passes (kept 10 iterations apart since the last
// check, bisected) counts as passed and is the least worst from then on
// (later iterates count when better than it); if the last check fails, the
// descent ends on the last iterate that passed.
// Acceptance: every tet with a moved node is certified
// (highorder::certify_tet; undecided = not positive) and measured on every
// sample of the convention. A tet that is not positive, exceeds the input's
// max AMIPS, or falls below min(min_scaled_jacobian, the input's min scaled
// Jacobian) gets its nodes back and keeps them while the others go on from
// where they are (from the input if putting the nodes back inverts a tet
// sharing them; up to 4 rounds); after the last round failing tets get
// their nodes back and their neighbours are checked again, until none is
// left.
// Restoring every node gives the input back, so the result is always
// certified and never worse at its worst.
// Deterministic for any thread count: per-tet terms are computed in parallel
// and summed in tet order.
#include "curvetet/highorder/quality.hpp"
#include "curvetet/mesh/tet_mesh.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace curvetet::volume {

struct CurvedDescentOptions {
  int power = 8;                     // p (even)
  int max_iterations = 1000;
  int checkpoint_iterations = 100;   // the best iterate so far is checked this often (see lbfgs)
  int memory = 8;                    // L-BFGS pairs kept
  int window = 10;                   // iterations over which...
  double min_decrease = 0.01;        // ...E must fall by this fraction to go on
  int worst_window = 150;            // stops when over this many iterations...
  double min_worst_decrease = 0.01;  // ...the least worst has fallen by less than this fraction
  int first_window = 100;            // ...or over this many from the start
  double min_scaled_jacobian = 0.05; // floor (see above)
  double active_ratio = 0.5;         // moves the tets within this ratio of the worst AMIPS or scaled J...
  int rings = 1;                     // ...and these layers of tets around them
  double gradient_share = 1e-3;      // the tets whose terms make less than this share of E add no gradient
};

struct CurvedDescentStats {
  int free_nodes = 0, iterations = 0;
  int held_tets = 0;     // tets kept as they were, the others optimized again
  int restored_tets = 0; // after the last round, tets given their nodes back alone
  double energy_before = 0, energy_after = 0; // E / (number of points), before restoring
  double seconds = 0;
  nlohmann::json json() const;
};

// `quality` (optional): each tet's highorder::tet_quality, of the input
// mesh on entry (then not measured again) and of the result on return.
CurvedDescentStats descend_curved(mesh::TetMesh& mesh, const CurvedDescentOptions& options = {},
                                  std::vector<highorder::TetQuality>* quality = nullptr);

} // namespace curvetet::volume

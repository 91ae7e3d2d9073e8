#pragma once
// The four local operations of the shell (paper App. B; Jiang et al. 2020
// §3.4). Each only proposes: it checks the topology, then builds the
// candidate star as plain arrays (star.hpp). The invariant list decides, the
// editor commits; the scheduler (coarsen.cpp) chooses which to try.
//
// All four keep the star's outer boundary (the pillars over the link edges)
// unchanged. Faces keep the shell's orientation (ccw seen from the top).
#include "curvetet/shell/shell_editor.hpp"
#include "curvetet/shell/star.hpp"

#include <optional>
#include <vector>

namespace curvetet::shell {

// The two faces of edge (a, b): first the one with a -> b, then b -> a, and
// their third vertices c and d. nullopt if the edge does not exist.
struct EdgeFaces {
  int f_ab, f_ba, c, d;
};
std::optional<EdgeFaces> edge_faces(const ShellEditor& e, int a, int b);

// Collapse `from` into `to` (to keeps its B, V, T). Topology: link condition
// (common neighbours are exactly the two opposite vertices) and the opposite
// vertices keep valence >= 3.
std::optional<StarCandidate> collapse_candidate(const ShellEditor& e, int from, int to);

// Pillar re-aiming (the collapse below, vertex smoothing at the end): the
// target pillar length and the singularity threshold of the direction.
struct SmoothParams {
  double target_pillar = 0; // absolute
  double singular_dot = 1e-3;
};

// The same collapse with `to`'s pillar re-aimed to the extrusion direction of
// its new star and grown toward target_pillar, as the pillar smoothing does:
// the star then also holds `to`'s other faces, unchanged. For where `to`'s
// old pillar leaves the new prisms inverted, e.g. where the collapse cuts
// across a sharp corner.
// `collapse`: a candidate of collapse_candidate.
std::optional<StarCandidate> collapse_reaimed_candidate(const ShellEditor& e, const StarCandidate& collapse,
                                                        const SmoothParams& p);

// Flip edge (a, b) of faces (a, b, c), (b, a, d) to (c, d): faces (a, d, c),
// (d, b, c). Topology: c, d not adjacent, a and b keep valence >= 3.
std::optional<StarCandidate> flip_candidate(const ShellEditor& e, int a, int b);
// Change of sum (valence - 6)^2 over a, b, c, d if (a, b) were flipped.
int flip_valence_gain(const ShellEditor& e, int a, int b);

// Split edge (a, b) at a new vertex m (id kNewVertex): faces (a, m, c),
// (m, b, c), (b, m, d), (m, a, d). m's middle is an input point in the
// preimage of the edge (App. B): where the fiber of the edge's midpoint meets
// a tracked input face. m's bottom and top are the midpoints of the edge's
// bottom and top edges (the caps stay flat there). nullopt if the fiber
// meets no tracked face (numerically).
std::optional<StarCandidate> split_candidate(const ShellEditor& e, int a, int b);

// Vertex smoothing of non-singular v, alternatives in order of preference:
//   pan + pillar:  middle moved to the input vertex (of the star's tracked
//                  faces) nearest to the centroid of its neighbours' middles,
//                  pillar re-aimed and grown as below
//   pan:           middle moved there, bottom and top translated with it
//   pillar:        "rotate" the pillar to the best extrusion direction of the
//                  star's middle faces, "zoom" each side's length toward
//                  target_pillar (at most x1.5 per step)
std::vector<StarCandidate> smooth_candidates(const ShellEditor& e, int v, const SmoothParams& p);

} // namespace curvetet::shell

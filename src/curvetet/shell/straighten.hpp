#pragma once
// Feature straightening (paper §5.1): the shell parametrises M̄, a copy of
// the input whose feature chain vertices lie on the straight coarse middle
// edges, so that Π maps every input chain onto its coarse edge (and ψ then
// onto the curved output edge). shell.hpp says how M̄ is stored.
//
// Each operation that creates or changes coarse feature edges moves the
// input chain vertices strictly inside their ranges to the arc-length point
// of the new straight edge (the correspondence of features.hpp), and puts
// the vertices that became edge ends back at their input position. The
// faces around the moved vertices are "reshaped"; the operation is kept only
// if M̄ stays a section of the shell, which the invariant below decides with
// exact predicates:
//  - every reshaped face keeps its orientation and a relative area > 1e-10
//    (β stays locally injective);
//  - it stays inside the new prisms and the "ring" (the live prisms sharing a
//    vertex with the star): it meets the ring's caps and the pillar quads
//    bounding star + ring (cut as the prisms cut them) at most at its own
//    corners, bitwise; with Coverage (meets a new prism, crosses no new cap)
//    it lies in their union;
//  - the new prisms it meets track it (Coverage) and pass Section with it;
//    every ring prism that meets or tracks it passes the section condition
//    with it, and starts tracking it (c.ring_tracked) when it meets it.
// The ring's vertices are star vertices' neighbours, locked for the batch
// (coarsen.cpp), so no other operation of the batch changes the ring; two
// operations of one batch must not reshape the same input face
// (ShellEditor::reshaped_in_batch).
// Points on M̄ are rounded to doubles; the checks run on the rounded points
// and the images of straightened vertices are then put exactly on their
// edge (a rounding away).
#include "curvetet/shell/star_invariants.hpp"

#include <array>
#include <memory>

namespace curvetet::shell {

// M̄ as candidate c leaves it.
Vec3 straight_vertex(const Shell& s, const StarCandidate& c, int input_vertex);
// Whether tracked point p lies on a coarse feature edge after c (straightened
// by c, or earlier and not moved back by c): its image is snapped onto that
// edge (snap_straightened_images), not found by containment.
bool on_straightened_edge(const Shell& s, const StarCandidate& c, int p);
// Tracked point p (shell.hpp straight_point) with c's straightening applied.
Vec3 straight_point(const Shell& s, const StarCandidate& c, int p);
std::array<Vec3, 3> straight_triangle(const Shell& s, const StarCandidate& c, int input_face);

// Fills c.straightened and c.reshaped and checks the rules above (also
// rejects what plan_feature_edit forbids). Needs c.geoms; runs before
// Coverage, which then tracks the reshaped faces where they now lie.
std::unique_ptr<StarInvariant> make_straightening_invariant();

// Puts the images of straightened chain vertices (by c or earlier:
// ShellFeatures::on_edge) exactly on their edge, in a new prism on that edge
// tracking the point's face. false: none does.
bool snap_straightened_images(const Shell& s, StarCandidate& c);

// Commit: writes c's new M̄ positions into s.straight (and where they lie
// into s.features.on_edge, kNewVertex read as `new_vertex`) and the ring's
// new tracked faces.
void apply_straightening(Shell& s, const StarCandidate& c, int new_vertex);

} // namespace curvetet::shell

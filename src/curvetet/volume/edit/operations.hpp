#pragma once
// Local operations of the curved optimization (paper §4.3, end), as
// proposals only: each checks the topology (frozen vertices, one region,
// link condition, no duplicate entity) and says which live tets die and
// which tets (corners in positive order, region tag) replace them. Running
// a proposal, checking the new tets and committing or rolling back is the
// scheduler's job (curved_remesh.cpp).
//
//  collapse(a -> b)   a (not frozen) merges into b, which stays where it is:
//                     the tets on edge ab die, a's other tets take b. Link
//                     condition lk(a) ∩ lk(b) = lk(ab), the boundary closed
//                     by a vertex at infinity, so that no boundary face
//                     doubles and no entity is duplicated.
//  remove_edge(a, b)  the n tets around an interior edge (n = 3: the 3-2
//                     flip, n = 4: the 4-4 flip, up to kMaxRing) replaced by
//                     2(n - 2) tets over a triangulation of the ring: one
//                     proposal per triangulation.
//  split(a, b)        a new vertex at the midpoint of an interior edge; each
//                     tet on the edge becomes two.
//  flip_face(t, f)    the 2-3 flip: the two tets on an interior face become
//                     three around the edge joining their apexes.
#include "curvetet/volume/edit/invariants.hpp"
#include "curvetet/volume/edit/tet_editor.hpp"

#include <utility>
#include <vector>

namespace curvetet::volume::edit {

struct Proposal {
  std::vector<int> kill;
  std::vector<std::pair<Corners, int>> add; // corners, tag; kNewVertex = the new vertex
  bool adds_vertex = false;
  Vec3 new_vertex = Vec3::Zero();
  // New edges, faces and interiors keep their straight nodes instead of
  // TetEditor::relax_new_nodes' (which can bend a flat new tet inside out).
  bool straight_new_nodes = false;
};
constexpr int kNewVertex = -1;

constexpr int kMaxRing = 6; // triangulations: 1, 2, 5, 14 for n = 3..6

// Each returns false with *why set when the topology forbids the operation.
bool collapse(const TetEditor& e, int a, int b, Proposal& out, Reject* why);
bool remove_edge(const TetEditor& e, int a, int b, std::vector<Proposal>& out, Reject* why);
bool flip_face(const TetEditor& e, int t, int face, Proposal& out, Reject* why);
bool split(const TetEditor& e, int a, int b, Proposal& out, Reject* why);

} // namespace curvetet::volume::edit

#pragma once
// The combinatorial core every editor of the volume stage shares (DESIGN.md
// §9): tets as corner quadruples in slots that stay valid after a kill,
// each vertex's star (its live tets, in the order they joined it), and the
// queries operations ask of them. The linear fill's optimizer
// (volume/exact_optimizer.hpp), face recovery (volume/face_recovery.cpp)
// and the curved optimization's editor (tet_editor.hpp) each keep their own
// geometry, transactions and checks on top of it.
//
// kill() keeps the order of the other tets in each star and add() appends,
// so a scheduler that walks stars makes the same choices whatever editor
// it runs on.
#include <array>
#include <vector>

namespace curvetet::volume::edit {

using Corners = std::array<int, 4>;

class TetStars {
 public:
  TetStars() = default;
  // Slots 0..tets.size()-1, all alive, over vertices [0, num_vertices).
  TetStars(std::vector<Corners> tets, int num_vertices);

  int num_slots() const { return static_cast<int>(corners_.size()); }
  int num_vertices() const { return static_cast<int>(star_.size()); }
  bool alive(int t) const { return alive_[t] != 0; }
  const Corners& corners(int t) const { return corners_[t]; }
  const std::vector<Corners>& all_corners() const { return corners_; } // dead slots included
  const std::vector<int>& star(int v) const { return star_[v]; }

  // A vertex with an empty star; returns its id.
  int add_vertex();
  // A new live slot (its id) joining its corners' stars.
  int add(const Corners& c);
  // Slot t leaves its corners' stars and is dead from now on.
  void kill(int t);
  // Live tet t takes corner `to` where it had `from` (leaving from's star,
  // joining to's): the collapse of `from` onto `to`.
  void rename_corner(int t, int from, int to);
  // For undo journals: dead slot t lives again (joining its corners' stars
  // at their end); the last slot, alive, goes; the last vertex, starless,
  // goes.
  void revive(int t);
  void pop_slot();
  void pop_vertex();

  bool has_edge(int a, int b) const;
  bool has_face(int a, int b, int c) const;
  // Live tets holding both a and b, in a's star order.
  std::vector<int> edge_ring(int a, int b) const;
  // The vertices around edge (a, b) (its tets `ring`) as a cycle, empty when
  // their fan is not closed (a boundary edge).
  std::vector<int> ring_cycle(int a, int b, const std::vector<int>& ring) const;
  // Vertices sharing a live tet with v, ascending.
  std::vector<int> neighbours(int v) const;

 private:
  std::vector<Corners> corners_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> star_;
};

} // namespace curvetet::volume::edit

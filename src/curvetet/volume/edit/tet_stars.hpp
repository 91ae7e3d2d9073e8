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
#include <algorithm>
#include <array>
#include <iterator>
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

  // Buffers for link_condition, reused across calls (it runs for every
  // collapse); one per thread.
  struct LinkBuffers {
    std::array<std::vector<std::array<int, 3>>, 3> tris;
    std::array<std::vector<std::array<int, 2>>, 4> edges;
    std::array<std::vector<int>, 4> verts;
  };
  // The link condition of the collapse of v onto u: lk(u) ∩ lk(v) = lk(uv)
  // as complexes (no triangle in both links, every edge and vertex in both
  // also in lk(uv)), over the tets of the stars that in_star(t) accepts (a
  // region). With the boundary closed by a vertex at infinity the caller
  // adds its own check (the linear optimizer's boundary_link_condition).
  template <class InStar>
  bool link_condition(int u, int v, LinkBuffers& buffers, InStar in_star) const;
  bool link_condition(int u, int v, LinkBuffers& buffers) const {
    return link_condition(u, v, buffers, [](int) { return true; });
  }

 private:
  std::vector<Corners> corners_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> star_;
};

template <class InStar>
bool TetStars::link_condition(int u, int v, LinkBuffers& buffers, InStar in_star) const {
  auto& [tu, tv, ct] = buffers.tris;
  auto& [eu, ev, euv, ce] = buffers.edges;
  auto& [pu, pv, puv, cp] = buffers.verts;
  const auto link = [&](int x, std::vector<std::array<int, 3>>& tris, std::vector<std::array<int, 2>>& edges,
                        std::vector<int>& verts) {
    tris.clear();
    edges.clear();
    verts.clear();
    for (const int t : star_[x]) {
      if (!in_star(t)) continue;
      std::array<int, 3> f;
      int j = 0;
      for (const int y : corners_[t])
        if (y != x) f[j++] = y;
      std::sort(f.begin(), f.end());
      tris.push_back(f);
      edges.push_back({f[0], f[1]});
      edges.push_back({f[0], f[2]});
      edges.push_back({f[1], f[2]});
      verts.insert(verts.end(), f.begin(), f.end());
    }
    std::sort(tris.begin(), tris.end());
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  };
  link(u, tu, eu, pu);
  link(v, tv, ev, pv);
  // lk(uv): the opposite edges of the tets holding both.
  euv.clear();
  puv.clear();
  for (const int t : star_[v]) {
    const Corners& q = corners_[t];
    if (!in_star(t) || std::find(q.begin(), q.end(), u) == q.end()) continue;
    std::array<int, 2> e;
    int j = 0;
    for (const int y : q)
      if (y != u && y != v) e[j++] = y;
    std::sort(e.begin(), e.end());
    euv.push_back(e);
    puv.push_back(e[0]);
    puv.push_back(e[1]);
  }
  std::sort(euv.begin(), euv.end());
  std::sort(puv.begin(), puv.end());
  puv.erase(std::unique(puv.begin(), puv.end()), puv.end());
  ct.clear();
  std::set_intersection(tu.begin(), tu.end(), tv.begin(), tv.end(), std::back_inserter(ct));
  if (!ct.empty()) return false;
  ce.clear();
  std::set_intersection(eu.begin(), eu.end(), ev.begin(), ev.end(), std::back_inserter(ce));
  for (const auto& e : ce)
    if (!std::binary_search(euv.begin(), euv.end(), e)) return false;
  cp.clear();
  std::set_intersection(pu.begin(), pu.end(), pv.begin(), pv.end(), std::back_inserter(cp));
  for (const int p : cp)
    if (!std::binary_search(puv.begin(), puv.end(), p)) return false;
  return true;
}

} // namespace curvetet::volume::edit

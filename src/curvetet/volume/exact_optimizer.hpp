#pragma once
// INTERNAL to volume/optimize*.cpp and volume/exact_optimizer_*.cpp: the
// linear fill's optimizer (paper §4.3 step 5) as one class, its operations
// in one file per kind:
//   exact_optimizer_mesh.cpp      transactions (journal), rounding; the tets
//                                 and their stars are edit::TetStars
//   exact_optimizer_smooth.cpp    energies, smoothing, worst-tet moves
//   exact_optimizer_collapse.cpp  collapses, the new-tet invariants, the
//                                 boundary's link condition
//   exact_optimizer_flips.cpp     2-3, 3-2 flips and edge removal
//   exact_optimizer_insert.cpp    splits, insertions, cavities
// and the schedule (passes, round_and_optimize) in optimize.cpp. What every
// operation keeps: optimize.hpp.
#include "curvetet/volume/edit/tet_stars.hpp"
#include "curvetet/volume/exact_mesh.hpp"
#include "curvetet/volume/fill.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace curvetet::volume::exact {

using Tet = std::array<int, 4>;

// Centre of the sphere through a, b, c, d (not finite for a flat tet).
inline Vec3 circumcentre(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  return a + (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) /
                 (2 * u.dot(v.cross(w)));
}
// Largest AMIPS energy a collapse may give a tet whose 4 vertices are frozen.
constexpr double kFrozenTetLimit = 6.0;
constexpr double kStale = std::numeric_limits<double>::quiet_NaN();

class Optimizer {
 public:
  Optimizer(ExactTetMesh&& m, FillStats& stats, const FillOptions& options);

  // A Steiner vertex on the surface: never rounded, smoothed or relocated
  // (that would move the boundary); only collapse_on_surface removes it.
  bool pinned(int v) const { return pinned_[v] != 0; }

  // Collapses the surface Steiner vertex v onto u (a vertex on the same
  // segment or in the same flat face, so the boundary keeps its shape).
  // Checks: every new tet positive (exact), the link condition including the
  // boundary (a virtual vertex joined to the boundary faces).
  // Largest energy of the tets collapse_on_surface(v, u) would create, or
  // +inf when that collapse is not allowed.
  double surface_collapse_cost(int v, int u) const;
  // The checks both share: every new tet positive, the link conditions;
  // `removed`: v's tets on edge (v, u); `worst` (optional) raised to the
  // largest energy of the new tets.
  // `why` (optional) says which check failed.
  bool surface_collapse_allowed(int v, int u, std::vector<int>& removed, double* worst,
                                FillReject* why = nullptr) const;

  bool collapse_on_surface(int v, int u);

  // Vertices, frozen flags and surface Steiner points; its `tets` is empty
  // while the optimizer runs (they live in TetStars: tet(), star()).
  ExactTetMesh& mesh() { return m_; }
  bool alive(int t) const { return stars_.alive(t); }
  const Tet& tet(int t) const { return stars_.corners(t); }

  double energy(const Tet& t) const;
  // Energy of live tet t, cached until it or one of its vertices changes.
  double tet_energy(int t);
  // The corners of t with v at p.
  std::array<const Vec3*, 4> corners_at(const Tet& t, int v, const Vec3& p) const;
  double energy_at(const Tet& t, int v, const Vec3& p) const;
  // The same energy cubed (the same order, without a cube root).
  double energy_cubed_at(const Tet& t, int v, const Vec3& p) const;
  // Energy of t with v at p, and its gradient with respect to v's position.
  double energy_gradient_at(const Tet& t, int v, const Vec3& p, Vec3& grad) const;
  // A new free vertex at double position p, in no tet yet.
  int add_vertex(const Vec3& p);
  void move(int v, const Vec3& p);

  // Rounds every rational vertex whose star stays positive; returns how many
  // are still rational.
  std::size_t round_pass();

  std::size_t count_rational() const;

  bool star_positive_at(int v, const Vec3& p) const;

  // --- smoothing: descend the star's sum of squared AMIPS energies without
  // raising its maximum; every tet stays positive (exact). A vertex whose
  // star did not change since its last failed attempt is not retried. ---
  bool smooth(int v);

  // Whether nothing in v's star (its tets, their vertices' positions)
  // changed after clock value `when` (0: never recorded).
  bool unchanged_since(int v, std::uint64_t when) const;
  std::uint64_t clock() const { return clock_; }
  // Whether every flip on t failed last time and nothing around it changed
  // since (the stars of its corners hold every tet those flips look at).
  bool flips_known_to_fail(int t) const;
  void mark_flips_failed(int t) { flip_failed_[t] = clock_; }

  // --- worst-tet smoothing: lowers the maximum energy of v's star by a
  // compass search (the gradient of the worst tet first, then the axes);
  // every accepted position keeps the star positive (exact). ---
  bool smooth_max(int v);

  // Moves an unrounded vertex to some double position keeping its star
  // positive (towards the star's centroid).
  bool relocate(int v);

  // --- collapse v onto u ---
  // What a collapse must keep besides positivity: nothing (for unrounded
  // vertices), quality (new worst <= old worst or the coarsening bound; no
  // new tet on frozen vertices only above kFrozenTetLimit, as smoothing can
  // never improve it; the sizing bound), or a strictly lower worst tet.
  enum class Keep { positivity, quality, lower_max };
  bool collapse(int v, int u, Keep keep);

  // --- flips ---
  // 3-2: interior edge (a, b) with exactly three tets around it.
  bool flip_32(int a, int b);
  // The same with the edge's tets known.
  bool flip_32(int a, int b, const std::vector<int>& ring);

  // Edge split for the worst tets: interior edge (a, b) (closed ring) gets a
  // new free vertex at its midpoint, which the compass search then places;
  // kept only if the ring's worst tet got strictly better, else undone (the
  // unused vertex stays starless and is dropped on extraction). A tet on a
  // sliver input face gets a new apex this way where its own is hemmed in.
  // The tets around edge (a, b) when it is interior (closed ring), else none.
  std::vector<int> interior_ring(int a, int b) const;
  // `ring`: interior_ring(a, b), non-empty.
  bool split_edge(int a, int b, const std::vector<int>& ring);

  // The same with a new vertex inside tet t (1-4 split from its centroid),
  // for worst tets whose edges all lie on the surface.
  bool split_tet(int t);

  // Replaces `old` by `parts` around the new vertex m, places m by the
  // compass search, and keeps the change only if m's star ends strictly
  // below old_max.
  bool commit_split(int m, const std::vector<int>& old, const std::vector<Tet>& parts, double old_max);

  // --- relocation through a cavity: for a free vertex hemmed in by its star
  // (e.g. a hair above a needle input face), where no smoothing step is
  // positive. The cavity starts as v's star and takes in the tet across
  // every face that `target` does not see strictly from inside; once the
  // cavity's boundary is a sphere seen from `target`, v moves there and is
  // joined to that boundary (a cone from a point seeing a sphere strictly
  // is a triangulation of the ball it bounds: the surface is untouched).
  // Kept only if the new tets' worst is strictly below the cavity's. ---
  static constexpr std::size_t kMaxCavity = 400;
  bool relocate_through_cavity(int v, const Vec3& target);

  // Inserts a new free vertex at p (a double point) inside the mesh, as in
  // Delaunay refinement: the cavity is the tets whose circumsphere holds p,
  // face-connected to the tet holding it (walked to from tet `from`), made
  // star-shaped as above. Kept only if the cavity's worst tet gets strictly
  // better.
  bool insert_vertex(int from, const Vec3& p);

  // The tet holding p (closed), walking from `from` toward p; -1 when the
  // walk leaves the mesh (p is outside) or takes too long.
  int locate(int from, const Vec3& p) const;
  // orient3d of tet c whose corner -1 is the double point p.
  int orient_with(const Tet& c, const Vec3& p) const;
  // Whether p is strictly inside tet t's circumsphere (doubles: it only
  // chooses the cavity; its validity is decided exactly by restar()).
  bool in_circumsphere(int t, const Vec3& p) const;

  // Replaces `seed` (tets, marked or not) by the cone from v at target over
  // the boundary of a cavity grown from it: the cavity takes in the tet
  // across every boundary face that target does not see strictly from
  // inside; once its boundary is a sphere seen from target, v moves there
  // and is joined to that boundary (a cone from a point seeing a sphere
  // strictly triangulates the ball it bounds; the surface is untouched).
  // Faces through v are inside its star. Kept only if the new tets' worst is
  // strictly below the cavity's, at target or (with `search`) at a point the
  // compass search finds from there that still sees every face strictly;
  // then the compass search polishes v.
  bool restar(int v, const Vec3& target, const std::vector<int>& seed, bool search = false);
  // Whether the oriented faces (tet, corner) form one closed sphere: every
  // edge in two faces, every vertex's link one cycle, V - E + F = 2.
  bool bounds_sphere(const std::vector<std::pair<int, int>>& faces) const;
  // The tet across the face of t opposite its corner k, or -1. A neighbour
  // found is kept in across_ while it lives (a tet's corners change only in
  // merge(), which forgets its entries).
  int across(int t, int k) const;
  // Where v would best sit for tet t alone (a compass search on its energy,
  // blind to the rest of the mesh): the target of a relocation.
  Vec3 best_corner(int t, int v) const;

  // Edge removal (4-4, 5-6, 6-8, 7-10 flips; 3-2 is flip_32): interior edge
  // (a, b) with a closed ring of k tets is replaced by the fan of the ring
  // polygon whose worst tet is best, when that is below the ring's worst.
  // The only flip that changes tets whose four vertices are all frozen
  // beyond 2-3 and 3-2.
  // `ring`: the edge's tets (edge_ring).
  bool remove_edge(int a, int b, const std::vector<int>& ring);

  // Edge removal then 3-2 flips (coarsening): interior edge (a, b) with a
  // closed ring c0..c(k-1) of k = 4..6 tets is replaced by 2(k-2) tets
  // (the ring polygon fanned from one c_i, joined to a and to b); that takes
  // tets from the edges (a or b, c_m), and the whole change is kept only if
  // 3-2 flips of those edges then leave fewer than k tets.
  bool remove_edge_then_32(int a, int b);

  std::vector<int> edge_ring(int a, int b) const { return stars_.edge_ring(a, b); }

  // The ring of interior edge (a, b) (its tets `ring`) as a vertex cycle,
  // empty when the fan around the edge is open (a boundary edge).
  std::vector<int> ring_cycle(int a, int b, const std::vector<int>& ring) const { return stars_.ring_cycle(a, b, ring); }

  // False when the fan of fan_tets(a, b, c, i) surely has a tet of energy
  // at least `bound`, by the doubles alone: a tet's energy in the orientation
  // the exact test gives it is never below the smaller of its two
  // orientations'. Most fans of a bad tet's edges fail here, before the
  // edge lookups and exact orientations of fan_tets.
  bool fan_may_beat(int a, int b, const std::vector<int>& c, int i, double bound) const;

  // Tets of the ring polygon c fanned from c[i], joined to a and to b, all
  // positive; empty when that is not a valid replacement: a fan diagonal
  // is already an edge, or a and b do not lie on opposite sides of every
  // fan triangle (then positive tets with the old boundary tile the old
  // region exactly).
  std::vector<Tet> fan_tets(int a, int b, const std::vector<int>& c, int i) const;

  // Opens a transaction: kill() and add() record into journal_ (and the
  // change stamps they overwrite into saved_touched_) until journaling_ is
  // reset.
  void begin_journal();
  // Undoes the transaction recorded in journal_: the tets it added that are
  // still alive go, and copies of the tets it killed that existed before it
  // come back (keeping their flip stamps). The change stamps go back too, so
  // an undone operation does not count as a change around it.
  void undo_journal();

  // 2-3: interior face of tet t opposite its corner k.
  bool flip_23(int t, int k);

  std::vector<int> neighbours(int v) const { return stars_.neighbours(v); }
  int num_tets() const { return stars_.num_slots(); } // slots, dead ones included
  std::size_t num_alive() const;
  const std::vector<int>& star(int v) const { return stars_.star(v); }

  mesh::LinearTetMesh extract(int num_keep);

 private:
  // Commits the collapse of v onto u: the tets of edge (u, v) go, v's
  // other tets take u instead.
  void merge(int v, int u, const std::vector<int>& removed);

  // The star's descent step of smooth().
  bool descend(int v);

  // The compass search of smooth_max(); see descend_max() for `goal`.
  bool compass_search(int v, double goal = std::numeric_limits<double>::infinity());
  double max_energy_at(const std::vector<Tet>& tets, int v, const Vec3& q, int* worst) const;
  // Compass search, with the worst tet's descent direction tried first, for
  // a position p of v in `tets` (all holding v) with a lower worst energy;
  // valid(q) must hold at every position taken. Returns the worst energy at
  // the final p. With a `goal`, gives up early when that looks out of reach.
  template <class Valid>
  double descend_max(const std::vector<Tet>& tets, int v, Vec3& p, Valid valid,
                     double goal = std::numeric_limits<double>::infinity()) const;

  ExactTetMesh m_;
  FillStats& stats_;
  double coarsen_energy_;  // FillOptions::coarsen_energy
  double max_edge_length_; // FillOptions::max_edge_length
  bool journaling_ = false;
  std::vector<std::pair<int, bool>> journal_; // (tet, added) of the open transaction
  std::vector<std::pair<int, std::uint64_t>> saved_touched_; // (vertex, touched_ before) in it
  edit::TetStars stars_; // the tets (m_.tets is left empty)
  mutable std::vector<std::array<int, 4>> across_; // per tet: neighbours found so far (-1: not known)
  mutable edit::TetStars::LinkBuffers link_buffers_;
  std::vector<double> energy_; // per tet; kStale until computed
  std::vector<std::uint64_t> flip_failed_; // per tet: clock_ of its last failed flip_pass visit, or 0
  // Change stamps: touched_[x] = clock_ when x moved or a tet at x changed;
  // smooth_failed_[x], max_failed_[x] = clock_ at x's last failed smoothing.
  std::uint64_t clock_ = 1;
  std::vector<std::uint64_t> touched_, smooth_failed_, max_failed_;
  std::vector<char> pinned_;
  std::vector<std::uint64_t> cavity_mark_; // per tet: == cavity_stamp_ while in the cavity
  std::uint64_t cavity_stamp_ = 0;

  // Boundary faces (x, p, q) around x, as sorted (p, q): faces of one tet.
  std::vector<std::array<int, 2>> boundary_link(int x) const;
  // With the virtual vertex w joined to the boundary: w in lk(u) ∩ lk(v)
  // needs uv on the boundary; a vertex p in both boundary links needs the
  // boundary face (u, v, p); an edge in both would duplicate a face.
  bool boundary_link_condition(int u, int v) const;

  // The invariants the new tets of a collapse or flip must keep, as one list
  // run in this order (cheapest first; the first broken is the reason
  // counted):
  //   energy             every new tet's energy <= max_energy (< if strict);
  //                      counted as energy_reason
  //   frozen_tet_energy  (frozen_limit) a new tet on frozen vertices only, which
  //                      no smoothing can improve, within kFrozenTetLimit or
  //                      the coarsening bound
  //   sizing             (sizing_from >= 0) no new edge from that vertex longer
  //                      than the sizing bound
  //   positivity         every new tet positive by exact orient3d
  struct NewTetRule {
    double max_energy = std::numeric_limits<double>::infinity();
    bool strict = false;
    FillReject energy_reason = FillReject::energy;
    bool frozen_limit = false;
    int sizing_from = -1;
  };
  std::optional<FillReject> broken_invariant(const std::vector<Tet>& tets, const NewTetRule& rule) const;

  // Counts r in FillStats::rejected; `return reject(r);` where a check fails.
  bool reject(FillReject r) const {
    ++stats_.rejected[static_cast<int>(r)];
    return false;
  }
  // Whether a new edge (a, b) would break the sizing bound.
  bool too_long(int a, int b) const;
  void kill(int t);
  int add(const Tet& t);
  bool edge_exists(int a, int b) const { return stars_.has_edge(a, b); }
  bool face_exists(int a, int b, int c) const { return stars_.has_face(a, b, c); }
  // lk(u) ∩ lk(v) = lk(uv) (v interior, so no virtual boundary vertex).
  bool link_condition(int u, int v) const { return stars_.link_condition(u, v, link_buffers_); }
};

// Used by the smoothing and the insertions (restar).
template <class Valid>
double Optimizer::descend_max(const std::vector<Tet>& tets, int v, Vec3& p, Valid valid, double goal) const {
  double len = 0;
  for (const Tet& t : tets)
    for (int x : t)
      if (x != v) len += (m_.v.d[x] - p).norm();
  len /= 3.0 * static_cast<double>(tets.size());
  int worst = 0;
  double best = max_energy_at(tets, v, p, &worst);
  if (!(len > 0)) return best;
  // The steps compare energies cubed (no cube root in the inner loop).
  double best3 = best * best * best;
  auto max_cubed_at = [&](const Vec3& q, int& w) {
    double m = 0;
    for (int i = 0; i < static_cast<int>(tets.size()); ++i) {
      const double e = energy_cubed_at(tets[i], v, q);
      if (e >= best3) return e; // enough to reject q
      if (e > m) {
        m = e;
        w = i;
      }
    }
    return m;
  };
  for (double step = 0.2 * len; step > 1e-3 * len;) {
    Vec3 g = Vec3::Zero();
    energy_gradient_at(tets[worst], v, p, g);
    std::array<Vec3, 7> dirs = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(),
                                Vec3::UnitZ(), -Vec3::UnitZ(), Vec3::Zero()};
    if (g.allFinite() && g.norm() > 0) dirs[6] = -g.normalized();
    bool improved = false;
    for (int i = 6; i >= 0 && !improved; --i) {
      if (dirs[i].isZero()) continue;
      const Vec3 q = p + step * dirs[i];
      int w = 0;
      const double e3 = max_cubed_at(q, w);
      if (!(e3 < best3) || !valid(q)) continue;
      p = q;
      best3 = e3;
      worst = w;
      improved = true;
    }
    if (!improved) {
      step *= 0.5;
      // Still far above `goal` once the steps have shrunk: it will not get
      // below it (of the searches that did, none was 25 % above after two
      // halvings; thingi10k's passes spent most of their time on the
      // others).
      const double give_up = goal * (1 + 5 * step / len);
      if (best3 > give_up * give_up * give_up) break;
    }
  }
  return max_energy_at(tets, v, p, nullptr);
}

} // namespace curvetet::volume::exact

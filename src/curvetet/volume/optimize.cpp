#include "curvetet/volume/optimize.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/highorder/quality.hpp"
#include "curvetet/volume/mesh_keys.hpp"
#include "curvetet/volume/tet_amips.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <cstdint>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numeric>

namespace curvetet::volume::exact {

namespace {

using Tet = std::array<int, 4>;

// Centre of the sphere through a, b, c, d (not finite for a flat tet).
Vec3 circumcentre(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  return a + (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) /
                 (2 * u.dot(v.cross(w)));
}
// Largest AMIPS energy a collapse may give a tet whose 4 vertices are frozen.
constexpr double kFrozenTetLimit = 6.0;
constexpr double kStale = std::numeric_limits<double>::quiet_NaN();

class Optimizer {
 public:
  Optimizer(ExactTetMesh&& m, FillStats& stats, const FillOptions& options)
      : m_(std::move(m)), stats_(stats), coarsen_energy_(options.coarsen_energy),
        max_edge_length_(options.max_edge_length) {
    vt_.resize(m_.v.size());
    for (int t = 0; t < static_cast<int>(m_.tets.size()); ++t)
      for (int x : m_.tets[t]) vt_[x].push_back(t);
    alive_.assign(m_.tets.size(), 1);
    across_.assign(m_.tets.size(), {-1, -1, -1, -1});
    energy_.assign(m_.tets.size(), kStale);
    flip_failed_.assign(m_.tets.size(), 0);
    touched_.assign(m_.v.size(), 0);
    smooth_failed_.assign(m_.v.size(), 0);
    max_failed_.assign(m_.v.size(), 0);
    pinned_.assign(m_.v.size(), 0);
    for (const auto& st : m_.on_surface) pinned_[st.vertex] = 1;
  }

  // A Steiner vertex on the surface: never rounded, smoothed or relocated
  // (that would move the boundary); only collapse_on_surface removes it.
  bool pinned(int v) const { return pinned_[v] != 0; }

  // Collapses the surface Steiner vertex v onto u (a vertex on the same
  // segment or in the same flat face, so the boundary keeps its shape).
  // Checks: every new tet positive (exact), the link condition including the
  // boundary (a virtual vertex joined to the boundary faces).
  // Largest energy of the tets collapse_on_surface(v, u) would create, or
  // +inf when that collapse is not allowed.
  double surface_collapse_cost(int v, int u) const {
    double worst = 0;
    bool shares = false;
    for (int t : vt_[v]) {
      const Tet& q = m_.tets[t];
      if (std::find(q.begin(), q.end(), u) != q.end()) {
        shares = true;
        continue;
      }
      Tet n = q;
      for (int& x : n)
        if (x == v) x = u;
      if (m_.v.orient(n[0], n[1], n[2], n[3]) <= 0) return std::numeric_limits<double>::infinity();
      worst = std::max(worst, energy(n));
    }
    if (!shares || !link_condition(u, v) || !boundary_link_condition(u, v))
      return std::numeric_limits<double>::infinity();
    return worst;
  }

  bool collapse_on_surface(int v, int u) {
    std::vector<int> removed;
    for (int t : vt_[v]) {
      const Tet& q = m_.tets[t];
      if (std::find(q.begin(), q.end(), u) != q.end()) {
        removed.push_back(t);
        continue;
      }
      Tet n = q;
      for (int& x : n)
        if (x == v) x = u;
      if (m_.v.orient(n[0], n[1], n[2], n[3]) <= 0) return false;
    }
    if (removed.empty()) return false;
    if (!link_condition(u, v) || !boundary_link_condition(u, v)) return false;
    merge(v, u, removed);
    pinned_[v] = 0;
    ++stats_.collapses;
    return true;
  }

  ExactTetMesh& mesh() { return m_; }
  bool alive(int t) const { return alive_[t]; }

  double energy(const Tet& t) const {
    const auto& d = m_.v.d;
    return tet_amips(d[t[0]], d[t[1]], d[t[2]], d[t[3]]);
  }
  // Energy of live tet t, cached until it or one of its vertices changes.
  double tet_energy(int t) {
    if (std::isnan(energy_[t])) energy_[t] = energy(m_.tets[t]);
    return energy_[t];
  }
  // The corners of t with v at p.
  std::array<const Vec3*, 4> corners_at(const Tet& t, int v, const Vec3& p) const {
    std::array<const Vec3*, 4> x;
    for (int k = 0; k < 4; ++k) x[k] = t[k] == v ? &p : &m_.v.d[t[k]];
    return x;
  }
  double energy_at(const Tet& t, int v, const Vec3& p) const {
    const auto x = corners_at(t, v, p);
    return tet_amips(*x[0], *x[1], *x[2], *x[3]);
  }
  // The same energy cubed (the same order, without a cube root).
  double energy_cubed_at(const Tet& t, int v, const Vec3& p) const {
    const auto x = corners_at(t, v, p);
    return tet_amips_cubed(*x[0], *x[1], *x[2], *x[3]);
  }
  // Energy of t with v at p, and its gradient with respect to v's position.
  double energy_gradient_at(const Tet& t, int v, const Vec3& p, Vec3& grad) const {
    const auto x = corners_at(t, v, p);
    const int corner = static_cast<int>(std::find(t.begin(), t.end(), v) - t.begin());
    return tet_amips_gradient(*x[0], *x[1], *x[2], *x[3], corner, grad);
  }
  // A new free vertex at double position p, in no tet yet.
  int add_vertex(const Vec3& p) {
    const int v = m_.v.add(p);
    m_.frozen.push_back(0);
    vt_.emplace_back();
    pinned_.push_back(0);
    touched_.push_back(++clock_);
    smooth_failed_.push_back(0);
    max_failed_.push_back(0);
    return v;
  }
  void move(int v, const Vec3& p) {
    m_.v.set(v, p);
    touched_[v] = ++clock_;
    for (int t : vt_[v]) energy_[t] = kStale;
  }

  // Rounds every rational vertex whose star stays positive; returns how many
  // are still rational.
  std::size_t round_pass() {
    std::size_t left = 0;
    for (int v = 0; v < m_.v.size(); ++v) {
      if (m_.v.exact[v] || vt_[v].empty() || pinned(v)) continue;
      const Vec3 p = nearest_double(m_.v.q[v]);
      if (star_positive_at(v, p)) {
        move(v, p);
      } else {
        ++left;
      }
    }
    return left;
  }

  std::size_t count_rational() const {
    std::size_t n = 0;
    for (int v = 0; v < m_.v.size(); ++v) n += !m_.v.exact[v] && !vt_[v].empty();
    return n;
  }

  bool star_positive_at(int v, const Vec3& p) const {
    for (int t : vt_[v])
      if (m_.v.orient_at(m_.tets[t], v, p) <= 0) return false;
    return true;
  }

  // --- smoothing: descend the star's sum of squared AMIPS energies without
  // raising its maximum; every tet stays positive (exact). A vertex whose
  // star did not change since its last failed attempt is not retried. ---
  bool smooth(int v) {
    if (unchanged_since(v, smooth_failed_[v])) return false;
    if (descend(v)) return true;
    smooth_failed_[v] = clock_;
    return false;
  }

  // Whether nothing in v's star (its tets, their vertices' positions)
  // changed after clock value `when` (0: never recorded).
  bool unchanged_since(int v, std::uint64_t when) const {
    if (when == 0 || touched_[v] > when) return false;
    for (int t : vt_[v])
      for (int x : m_.tets[t])
        if (touched_[x] > when) return false;
    return true;
  }
  std::uint64_t clock() const { return clock_; }
  // Whether every flip on t failed last time and nothing around it changed
  // since (the stars of its corners hold every tet those flips look at).
  bool flips_known_to_fail(int t) const {
    const std::uint64_t when = flip_failed_[t];
    return when != 0 && std::all_of(m_.tets[t].begin(), m_.tets[t].end(), [&](int x) { return unchanged_since(x, when); });
  }
  void mark_flips_failed(int t) { flip_failed_[t] = clock_; }

  // --- worst-tet smoothing: lowers the maximum energy of v's star by a
  // compass search (the gradient of the worst tet first, then the axes);
  // every accepted position keeps the star positive (exact). ---
  bool smooth_max(int v) {
    if (unchanged_since(v, max_failed_[v])) return false;
    if (compass_search(v)) return true;
    max_failed_[v] = clock_;
    return false;
  }

  // Moves an unrounded vertex to some double position keeping its star
  // positive (towards the star's centroid).
  bool relocate(int v) {
    if (m_.frozen[v] || pinned(v) || m_.v.exact[v]) return false;
    Vec3 c = Vec3::Zero();
    int n = 0;
    for (int t : vt_[v])
      for (int x : m_.tets[t])
        if (x != v) {
          c += m_.v.d[x];
          ++n;
        }
    c /= n;
    const Vec3 p0 = m_.v.d[v];
    for (double a : {1.0, 0.5, 0.25, 0.1, 0.01, 1e-3, 1e-5, 1e-8}) {
      const Vec3 p = p0 + a * (c - p0);
      if (star_positive_at(v, p)) {
        move(v, p);
        return true;
      }
    }
    return false;
  }

  // --- collapse v onto u ---
  // What a collapse must keep besides positivity: nothing (for unrounded
  // vertices), quality (new worst <= old worst or the coarsening bound; no
  // new tet on frozen vertices only above kFrozenTetLimit, as smoothing can
  // never improve it; the sizing bound), or a strictly lower worst tet.
  enum class Keep { positivity, quality, lower_max };
  bool collapse(int v, int u, Keep keep) {
    if (m_.frozen[v] || pinned(v) || u == v) return false;
    double old_max = 0;
    for (int t : vt_[v]) old_max = std::max(old_max, tet_energy(t));
    const double bound = std::max(old_max, coarsen_energy_);
    const bool require_quality = keep == Keep::quality;
    // The new tets: energy first (cheap), exact orientation last.
    std::vector<int> removed;
    for (int t : vt_[v]) {
      const Tet& q = m_.tets[t];
      if (std::find(q.begin(), q.end(), u) != q.end()) {
        removed.push_back(t);
        continue;
      }
      Tet n = q;
      for (int& x : n)
        if (x == v) x = u;
      if (require_quality) {
        const double e = energy(n);
        if (!(e <= bound)) return false;
        // A tet on frozen vertices only can never be smoothed: keep it good.
        if (e > std::max(kFrozenTetLimit, coarsen_energy_) && m_.frozen[n[0]] && m_.frozen[n[1]] && m_.frozen[n[2]] &&
            m_.frozen[n[3]])
          return false;
        for (int x : n)
          if (x != u && too_long(u, x) && !edge_exists(u, x)) return false;
      } else if (keep == Keep::lower_max && !(energy(n) < old_max)) {
        return false;
      }
      if (m_.v.orient(n[0], n[1], n[2], n[3]) <= 0) return false;
    }
    if (removed.empty()) return false; // not an edge
    if (!link_condition(u, v)) return false;
    merge(v, u, removed);
    ++stats_.collapses;
    return true;
  }

  // --- flips ---
  // 3-2: interior edge (a, b) with exactly three tets around it.
  bool flip_32(int a, int b) { return flip_32(a, b, edge_ring(a, b)); }
  // The same with the edge's tets known.
  bool flip_32(int a, int b, const std::vector<int>& ring) {
    if (ring.size() != 3) return false;
    std::vector<int> others;
    for (int t : ring)
      for (int x : m_.tets[t])
        if (x != a && x != b) others.push_back(x);
    std::sort(others.begin(), others.end());
    // closed ring: three vertices, each twice
    if (!(others.size() == 6 && others[0] == others[1] && others[2] == others[3] && others[4] == others[5] &&
          others[1] != others[2] && others[3] != others[4]))
      return false;
    const int c = others[0], d = others[2], e = others[4];
    if (face_exists(c, d, e)) return false;
    double old_max = 0;
    for (int t : ring) old_max = std::max(old_max, tet_energy(t));
    // a and b must lie strictly on opposite sides of cde (then ab pierces it).
    const int sa = m_.v.orient(c, d, e, a), sb = m_.v.orient(c, d, e, b);
    if (sa == 0 || sb != -sa) return false;
    Tet t1 = sa > 0 ? Tet{c, d, e, a} : Tet{d, c, e, a};
    Tet t2 = sa > 0 ? Tet{d, c, e, b} : Tet{c, d, e, b};
    const double new_max = std::max(energy(t1), energy(t2));
    if (!(new_max < old_max || new_max <= coarsen_energy_)) return false;
    for (int t : ring) kill(t);
    add(t1);
    add(t2);
    ++stats_.flips;
    return true;
  }

  // Edge split for the worst tets: interior edge (a, b) (closed ring) gets a
  // new free vertex at its midpoint, which the compass search then places;
  // kept only if the ring's worst tet got strictly better, else undone (the
  // unused vertex stays starless and is dropped on extraction). A tet on a
  // sliver input face gets a new apex this way where its own is hemmed in.
  // The tets around edge (a, b) when it is interior (closed ring), else none.
  std::vector<int> interior_ring(int a, int b) const {
    std::vector<int> ring = edge_ring(a, b);
    if (ring.size() < 3 || ring_cycle(a, b, ring).empty()) ring.clear();
    return ring;
  }
  // `ring`: interior_ring(a, b), non-empty.
  bool split_edge(int a, int b, const std::vector<int>& ring) {
    double old_max = 0;
    for (int t : ring) old_max = std::max(old_max, tet_energy(t));
    const Vec3 p = 0.5 * (m_.v.d[a] + m_.v.d[b]);
    std::vector<Tet> halves;
    for (int t : ring)
      for (int end : {a, b}) {
        Tet h = m_.tets[t];
        for (int& x : h)
          if (x == end) x = -1; // the new vertex
        halves.push_back(h);
      }
    // p may miss the segment by rounding: every half is checked exactly.
    const int m = add_vertex(p);
    for (Tet& h : halves) {
      for (int& x : h)
        if (x == -1) x = m;
      if (m_.v.orient(h[0], h[1], h[2], h[3]) <= 0) return false; // m stays starless
    }
    return commit_split(m, ring, halves, old_max);
  }

  // The same with a new vertex inside tet t (1-4 split from its centroid),
  // for worst tets whose edges all lie on the surface.
  bool split_tet(int t) {
    const Tet q = m_.tets[t];
    const double old_max = tet_energy(t);
    const int m = add_vertex(0.25 * (m_.v.d[q[0]] + m_.v.d[q[1]] + m_.v.d[q[2]] + m_.v.d[q[3]]));
    std::array<Tet, 4> parts;
    for (int k = 0; k < 4; ++k) {
      parts[k] = q;
      parts[k][k] = m;
      if (m_.v.orient(parts[k][0], parts[k][1], parts[k][2], parts[k][3]) <= 0) return false; // m stays starless
    }
    return commit_split(m, {t}, {parts.begin(), parts.end()}, old_max);
  }

  // Replaces `old` by `parts` around the new vertex m, places m by the
  // compass search, and keeps the change only if m's star ends strictly
  // below old_max.
  bool commit_split(int m, const std::vector<int>& old, const std::vector<Tet>& parts, double old_max) {
    begin_journal();
    for (int t : old) kill(t);
    for (const Tet& h : parts) add(h);
    journaling_ = false;
    compass_search(m, old_max);
    double new_max = 0;
    for (int t : vt_[m]) new_max = std::max(new_max, tet_energy(t));
    if (new_max < old_max) {
      ++stats_.splits;
      return true;
    }
    undo_journal();
    return false;
  }

  // --- relocation through a cavity: for a free vertex hemmed in by its star
  // (e.g. a hair above a needle input face), where no smoothing step is
  // positive. The cavity starts as v's star and takes in the tet across
  // every face that `target` does not see strictly from inside; once the
  // cavity's boundary is a sphere seen from `target`, v moves there and is
  // joined to that boundary (a cone from a point seeing a sphere strictly
  // is a triangulation of the ball it bounds: the surface is untouched).
  // Kept only if the new tets' worst is strictly below the cavity's. ---
  static constexpr std::size_t kMaxCavity = 400;
  bool relocate_through_cavity(int v, const Vec3& target) {
    if (m_.frozen[v] || pinned(v) || !m_.v.exact[v] || vt_[v].empty()) return false;
    if (!restar(v, target, vt_[v])) return false;
    ++stats_.relocations;
    return true;
  }

  // Inserts a new free vertex at p (a double point) inside the mesh, as in
  // Delaunay refinement: the cavity is the tets whose circumsphere holds p,
  // face-connected to the tet holding it (walked to from tet `from`), made
  // star-shaped as above. Kept only if the cavity's worst tet gets strictly
  // better.
  bool insert_vertex(int from, const Vec3& p) {
    const int holder = locate(from, p);
    if (holder < 0) return false;
    std::vector<int> cavity{holder};
    ++cavity_stamp_;
    cavity_mark_.resize(m_.tets.size(), 0);
    cavity_mark_[holder] = cavity_stamp_;
    for (std::size_t i = 0; i < cavity.size() && cavity.size() < kMaxCavity / 4; ++i)
      for (int k = 0; k < 4; ++k) {
        const int n = across(cavity[i], k);
        if (n < 0 || cavity_mark_[n] == cavity_stamp_ || !in_circumsphere(n, p)) continue;
        cavity_mark_[n] = cavity_stamp_;
        cavity.push_back(n);
      }
    const int m = add_vertex(p);
    if (!restar(m, p, cavity, /*search=*/true)) return false; // m stays starless (dropped on extraction)
    ++stats_.splits;
    return true;
  }

  // The tet holding p (closed), walking from `from` toward p; -1 when the
  // walk leaves the mesh (p is outside) or takes too long.
  int locate(int from, const Vec3& p) const {
    int t = from;
    for (int steps = 0; steps < 1000; ++steps) {
      const Tet& q = m_.tets[t];
      int exit = -1;
      for (int k = 0; k < 4 && exit < 0; ++k) {
        Tet c = q;
        c[k] = -1;
        if (orient_with(c, p) < 0) exit = k;
      }
      if (exit < 0) return t;
      t = across(t, exit);
      if (t < 0) return -1;
    }
    return -1;
  }
  // orient3d of tet c whose corner -1 is the double point p.
  int orient_with(const Tet& c, const Vec3& p) const {
    Vec3 x[4];
    for (int k = 0; k < 4; ++k) x[k] = c[k] < 0 ? p : m_.v.d[c[k]];
    return geometry::orient3d(x[0], x[1], x[2], x[3]);
  }
  // Whether p is strictly inside tet t's circumsphere (doubles: it only
  // chooses the cavity; its validity is decided exactly by restar()).
  bool in_circumsphere(int t, const Vec3& p) const {
    const Tet& q = m_.tets[t];
    const Vec3 centre = circumcentre(m_.v.d[q[0]], m_.v.d[q[1]], m_.v.d[q[2]], m_.v.d[q[3]]);
    return centre.allFinite() && (p - centre).squaredNorm() < (m_.v.d[q[0]] - centre).squaredNorm();
  }

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
  bool restar(int v, const Vec3& target, const std::vector<int>& seed, bool search = false) {
    std::vector<int> cavity = seed;
    ++cavity_stamp_;
    cavity_mark_.resize(m_.tets.size(), 0);
    for (int t : cavity) cavity_mark_[t] = cavity_stamp_;
    // Boundary faces as (tet, corner opposite): a new tet is that tet with v
    // at target in place of the corner.
    // Grow (each tet's faces are looked at once: a face seen strictly stays
    // so), then collect the faces still on the boundary.
    // (tet, corner, tet across): the across is kept for the final filter.
    std::vector<std::array<int, 3>> seen;
    for (std::size_t i = 0; i < cavity.size(); ++i) {
      const Tet& q = m_.tets[cavity[i]];
      const bool in_star = std::find(q.begin(), q.end(), v) != q.end();
      for (int k = 0; k < 4; ++k) {
        if (in_star && q[k] != v) continue;
        const int n = across(cavity[i], k);
        if (n >= 0 && cavity_mark_[n] == cavity_stamp_) continue;
        Tet c = q;
        c[k] = v;
        if (m_.v.orient_at(c, v, target) > 0) {
          seen.push_back({cavity[i], k, n});
          continue;
        }
        if (n < 0 || cavity.size() >= kMaxCavity) return false; // an input face blocks the target
        cavity_mark_[n] = cavity_stamp_;
        cavity.push_back(n);
      }
    }
    std::vector<std::pair<int, int>> faces;
    for (const auto& [t, k, n] : seen)
      if (n < 0 || cavity_mark_[n] != cavity_stamp_) faces.emplace_back(t, k);
    double old_max = 0;
    for (int t : cavity) old_max = std::max(old_max, tet_energy(t));
    std::vector<Tet> parts;
    bool better = true;
    for (auto [t, k] : faces) {
      Tet c = m_.tets[t];
      c[k] = v;
      better = better && energy_at(c, v, target) < old_max;
      if (!better && !search) return false; // before the costlier sphere check
      parts.push_back(c);
    }
    // An insertion may move its point within the cone's kernel first.
    Vec3 at = target;
    if (!better && !(descend_max(parts, v, at, [&](const Vec3& q) {
                       return std::all_of(parts.begin(), parts.end(),
                                          [&](const Tet& c) { return m_.v.orient_at(c, v, q) > 0; });
                     }, old_max) < old_max))
      return false;
    if (!bounds_sphere(faces)) return false;
    for (int t : cavity) kill(t);
    move(v, at);
    for (const Tet& c : parts) add(c);
    compass_search(v); // only ever lowers the star's worst
    return true;
  }
  // Whether the oriented faces (tet, corner) form one closed sphere: every
  // edge in two faces, every vertex's link one cycle, V - E + F = 2.
  bool bounds_sphere(const std::vector<std::pair<int, int>>& faces) const {
    std::vector<std::array<int, 3>> tris;
    for (auto [t, k] : faces) {
      std::array<int, 3> f;
      for (int i = 0, j = 0; i < 4; ++i)
        if (i != k) f[j++] = m_.tets[t][i];
      if (k % 2 == 0) std::swap(f[0], f[1]); // (f, corner k) has q's parity: one orientation for all
      tris.push_back(f);
    }
    std::vector<std::uint64_t> edges;
    std::vector<int> verts;
    for (const auto& f : tris)
      for (int i = 0; i < 3; ++i) {
        edges.push_back(edge_key(f[i], f[(i + 1) % 3]));
        verts.push_back(f[i]);
      }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size(); i += 2)
      if (i + 1 >= edges.size() || edges[i] != edges[i + 1] || (i + 2 < edges.size() && edges[i + 2] == edges[i]))
        return false;
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    if (static_cast<long>(verts.size()) - static_cast<long>(edges.size() / 2) + static_cast<long>(tris.size()) != 2)
      return false;
    // Link of x: the edges opposite x in its faces; one cycle iff a walk
    // from one link vertex visits them all (every link vertex has degree 2).
    for (int x : verts) {
      std::vector<std::array<int, 2>> link;
      for (const auto& f : tris)
        for (int i = 0; i < 3; ++i)
          if (f[i] == x) link.push_back({f[(i + 1) % 3], f[(i + 2) % 3]});
      std::size_t steps = 0;
      for (int at = link[0][1]; at != link[0][0]; ++steps) {
        const auto next = std::find_if(link.begin(), link.end(), [&](const auto& e) { return e[0] == at; });
        if (next == link.end() || steps > link.size()) return false;
        at = (*next)[1];
      }
      if (steps + 1 != link.size()) return false;
    }
    return true;
  }
  // The tet across the face of t opposite its corner k, or -1. A neighbour
  // found is kept in across_ while it lives (a tet's corners change only in
  // merge(), which forgets its entries).
  int across(int t, int k) const {
    if (const int n = across_[t][k]; n >= 0 && alive_[n]) return n;
    const Tet& q = m_.tets[t];
    int a = q[(k + 1) % 4], b = q[(k + 2) % 4], c = q[(k + 3) % 4];
    if (vt_[b].size() < vt_[a].size()) std::swap(a, b); // scan the smallest star
    if (vt_[c].size() < vt_[a].size()) std::swap(a, c);
    for (int s : vt_[a]) {
      if (s == t) continue;
      const Tet& r = m_.tets[s];
      const bool has_b = r[0] == b || r[1] == b || r[2] == b || r[3] == b;
      if (has_b && (r[0] == c || r[1] == c || r[2] == c || r[3] == c)) return across_[t][k] = s;
    }
    return -1;
  }
  // Where v would best sit for tet t alone (a compass search on its energy,
  // blind to the rest of the mesh): the target of a relocation.
  Vec3 best_corner(int t, int v) const {
    const Tet& q = m_.tets[t];
    Vec3 p = m_.v.d[v];
    double len = 0;
    for (int x : q) len += (m_.v.d[x] - p).norm();
    len /= 3;
    double best = energy_at(q, v, p);
    int iterations = 0;
    for (double step = len; step > 1e-3 * len && iterations < 500; ++iterations) {
      Vec3 g;
      energy_gradient_at(q, v, p, g);
      const std::array<Vec3, 7> dirs = {g.allFinite() && g.norm() > 0 ? Vec3(-g.normalized()) : Vec3(Vec3::UnitX()),
                                        Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(),
                                        Vec3::UnitZ(), -Vec3::UnitZ()};
      bool improved = false;
      for (const Vec3& d : dirs) {
        const double e = energy_at(q, v, p + step * d);
        if (e < best) {
          best = e;
          p += step * d;
          improved = true;
          break;
        }
      }
      if (!improved) step *= 0.5;
    }
    return p;
  }

  // Edge removal (4-4, 5-6, 6-8, 7-10 flips; 3-2 is flip_32): interior edge
  // (a, b) with a closed ring of k tets is replaced by the fan of the ring
  // polygon whose worst tet is best, when that is below the ring's worst.
  // The only flip that changes tets whose four vertices are all frozen
  // beyond 2-3 and 3-2.
  // `ring`: the edge's tets (edge_ring).
  bool remove_edge(int a, int b, const std::vector<int>& ring) {
    const int k = static_cast<int>(ring.size());
    if (k < 4 || k > 7) return false;
    const auto c = ring_cycle(a, b, ring);
    if (c.empty()) return false;
    double best_max = 0;
    for (int t : ring) best_max = std::max(best_max, tet_energy(t));
    std::vector<Tet> best;
    for (int i = 0; i < k; ++i) {
      if (!fan_may_beat(a, b, c, i, best_max)) continue;
      auto nt = fan_tets(a, b, c, i);
      double m = 0;
      for (const auto& t : nt) m = std::max(m, energy(t));
      if (!nt.empty() && m < best_max) {
        best_max = m;
        best = std::move(nt);
      }
    }
    if (best.empty()) return false;
    for (int t : ring) kill(t);
    for (const auto& t : best) add(t);
    ++stats_.flips;
    return true;
  }

  // Edge removal then 3-2 flips (coarsening): interior edge (a, b) with a
  // closed ring c0..c(k-1) of k = 4..6 tets is replaced by 2(k-2) tets
  // (the ring polygon fanned from one c_i, joined to a and to b); that takes
  // tets from the edges (a or b, c_m), and the whole change is kept only if
  // 3-2 flips of those edges then leave fewer than k tets.
  bool remove_edge_then_32(int a, int b) {
    std::vector<int> ring = edge_ring(a, b);
    const int k = static_cast<int>(ring.size());
    if (k < 4 || k > 6) return false;
    const auto c = ring_cycle(a, b, ring);
    if (c.empty()) return false;
    double old_max = 0;
    for (int t : ring) old_max = std::max(old_max, tet_energy(t));
    const double bound = std::max(old_max, coarsen_energy_);
    for (int i = 0; i < k; ++i) {
      const auto nt = fan_tets(a, b, c, i);
      if (nt.empty()) continue;
      double new_max = 0;
      for (const auto& t : nt) new_max = std::max(new_max, energy(t));
      if (!(new_max <= bound)) continue;
      begin_journal();
      ring = edge_ring(a, b); // an undone fan put back copies of the ring
      for (int t : ring) kill(t);
      for (const auto& t : nt) add(t);
      int removed = 0;
      for (bool progress = true; progress;) {
        progress = false;
        for (int m = 0; m < k; ++m)
          for (int end : {a, b})
            if (flip_32(end, c[m])) {
              ++removed;
              progress = true;
            }
      }
      journaling_ = false;
      if (removed > k - 4) { // 2(k-2) - removed < k
        ++stats_.flips;
        return true;
      }
      undo_journal();
      // try the next fan
    }
    return false;
  }

  std::vector<int> edge_ring(int a, int b) const {
    std::vector<int> ring;
    for (int t : vt_[a]) {
      const Tet& q = m_.tets[t];
      if (std::find(q.begin(), q.end(), b) != q.end()) ring.push_back(t);
    }
    return ring;
  }

  // The ring of interior edge (a, b) (its tets `ring`) as a vertex cycle,
  // empty when the fan around the edge is open (a boundary edge).
  std::vector<int> ring_cycle(int a, int b, const std::vector<int>& ring) const {
    std::vector<std::array<int, 2>> links;
    for (int t : ring) {
      std::array<int, 2> e;
      int j = 0;
      for (int x : m_.tets[t])
        if (x != a && x != b) e[j++] = x;
      links.push_back(e);
    }
    return volume::ring_cycle(links);
  }

  // False when the fan of fan_tets(a, b, c, i) surely has a tet of energy
  // at least `bound`, by the doubles alone: a tet's energy in the orientation
  // the exact test gives it is never below the smaller of its two
  // orientations'. Most fans of a bad tet's edges fail here, before the
  // edge lookups and exact orientations of fan_tets.
  bool fan_may_beat(int a, int b, const std::vector<int>& c, int i, double bound) const {
    const int k = static_cast<int>(c.size());
    const auto& d = m_.v.d;
    for (int j = 1; j <= k - 2; ++j) {
      const Vec3 &p = d[c[i]], &q = d[c[(i + j) % k]], &r = d[c[(i + j + 1) % k]];
      for (int apex : {a, b})
        if (std::min(tet_amips(p, q, r, d[apex]), tet_amips(q, p, r, d[apex])) >= bound) return false;
    }
    return true;
  }

  // Tets of the ring polygon c fanned from c[i], joined to a and to b, all
  // positive; empty when that is not a valid replacement: a fan diagonal
  // is already an edge, or a and b do not lie on opposite sides of every
  // fan triangle (then positive tets with the old boundary tile the old
  // region exactly).
  std::vector<Tet> fan_tets(int a, int b, const std::vector<int>& c, int i) const {
    const int k = static_cast<int>(c.size());
    for (int j = 2; j <= k - 2; ++j)
      if (edge_exists(c[i], c[(i + j) % k]) || too_long(c[i], c[(i + j) % k])) return {};
    std::vector<Tet> out;
    int sign = 0;
    for (int j = 1; j <= k - 2; ++j) {
      Tet ta{c[i], c[(i + j) % k], c[(i + j + 1) % k], a}, tb{c[i], c[(i + j) % k], c[(i + j + 1) % k], b};
      const int sa = m_.v.orient(ta[0], ta[1], ta[2], ta[3]), sb = m_.v.orient(tb[0], tb[1], tb[2], tb[3]);
      if (sa == 0 || sb != -sa || (sign != 0 && sa != sign)) return {};
      sign = sa;
      if (sa < 0) std::swap(ta[0], ta[1]);
      else std::swap(tb[0], tb[1]);
      out.push_back(ta);
      out.push_back(tb);
    }
    return out;
  }

  // Opens a transaction: kill() and add() record into journal_ (and the
  // change stamps they overwrite into saved_touched_) until journaling_ is
  // reset.
  void begin_journal() {
    journal_.clear();
    saved_touched_.clear();
    journaling_ = true;
  }
  // Undoes the transaction recorded in journal_: the tets it added that are
  // still alive go, and copies of the tets it killed that existed before it
  // come back (keeping their flip stamps). The change stamps go back too, so
  // an undone operation does not count as a change around it.
  void undo_journal() {
    const auto journal = std::move(journal_);
    journal_.clear();
    std::vector<int> added;
    for (const auto& [t, was_added] : journal)
      if (was_added) added.push_back(t);
    std::sort(added.begin(), added.end());
    for (const auto& [t, was_added] : journal)
      if (was_added && alive_[t]) kill(t);
    for (const auto& [t, was_added] : journal)
      if (!was_added && !std::binary_search(added.begin(), added.end(), t)) {
        const Tet copy = m_.tets[t]; // add() may reallocate m_.tets
        const std::uint64_t stamp = flip_failed_[t];
        flip_failed_[add(copy)] = stamp;
      }
    for (auto it = saved_touched_.rbegin(); it != saved_touched_.rend(); ++it) touched_[it->first] = it->second;
    saved_touched_.clear();
  }

  // 2-3: interior face of tet t opposite its corner k.
  bool flip_23(int t, int k) {
    const Tet q = m_.tets[t];
    const int d = q[k];
    std::array<int, 3> f;
    for (int i = 0, j = 0; i < 4; ++i)
      if (i != k) f[j++] = q[i];
    // (f0, f1, f2, d) is q up to moving corner k last: parity 3 - k.
    if ((3 - k) % 2 == 1) std::swap(f[0], f[1]);
    int other = -1;
    for (int s : vt_[f[0]]) {
      if (s == t) continue;
      const Tet& r = m_.tets[s];
      if (std::find(r.begin(), r.end(), f[1]) != r.end() && std::find(r.begin(), r.end(), f[2]) != r.end()) {
        other = s;
        break;
      }
    }
    if (other < 0) return false;
    int e = -1;
    for (int x : m_.tets[other])
      if (x != f[0] && x != f[1] && x != f[2]) e = x;
    if (edge_exists(d, e)) return false;
    const double old_max = std::max(tet_energy(t), tet_energy(other));
    std::array<Tet, 3> nt;
    double new_max = 0;
    for (int i = 0; i < 3; ++i) {
      nt[i] = {f[i], f[(i + 1) % 3], e, d}; // positive iff de pierces f
      if (!orient_positive(nt[i])) return false;
      new_max = std::max(new_max, energy(nt[i]));
    }
    if (!(new_max < old_max)) return false;
    kill(t);
    kill(other);
    for (auto& x : nt) add(x);
    ++stats_.flips;
    return true;
  }

  std::vector<int> neighbours(int v) const {
    std::vector<int> out;
    for (int t : vt_[v])
      for (int x : m_.tets[t])
        if (x != v) out.push_back(x);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  int num_tets() const { return static_cast<int>(m_.tets.size()); }
  std::size_t num_alive() const { return static_cast<std::size_t>(std::count(alive_.begin(), alive_.end(), 1)); }
  const std::vector<int>& star(int v) const { return vt_[v]; }

  mesh::LinearTetMesh extract(int num_keep) {
    mesh::LinearTetMesh out;
    std::vector<int> id(m_.v.size(), -1);
    for (int v = 0; v < num_keep; ++v) id[v] = v;
    int next = num_keep;
    for (int t = 0; t < num_tets(); ++t)
      if (alive_[t])
        for (int x : m_.tets[t])
          if (id[x] < 0) id[x] = next++;
    out.vertices.resize(next);
    for (int v = 0; v < m_.v.size(); ++v)
      if (id[v] >= 0) {
        if (!m_.v.exact[v]) throw Error(ExitCode::internal, "volume: a vertex could not be rounded to doubles");
        out.vertices[id[v]] = m_.v.d[v];
      }
    for (int t = 0; t < num_tets(); ++t)
      if (alive_[t]) {
        const Tet& q = m_.tets[t];
        out.tets.push_back({id[q[0]], id[q[1]], id[q[2]], id[q[3]]});
      }
    return out;
  }

 private:
  // Commits the collapse of v onto u: the tets of edge (u, v) go, v's
  // other tets take u instead.
  void merge(int v, int u, const std::vector<int>& removed) {
    for (int t : removed) kill(t);
    ++clock_;
    for (int t : std::vector<int>(vt_[v])) {
      across_[t] = {-1, -1, -1, -1};
      for (int& x : m_.tets[t])
        if (x == v) x = u;
      vt_[u].push_back(t);
      energy_[t] = kStale;
      for (int x : m_.tets[t]) touched_[x] = clock_;
    }
    vt_[v].clear();
  }

  // The star's descent step of smooth().
  bool descend(int v) {
    if (m_.frozen[v] || pinned(v) || vt_[v].empty()) return false;
    const Vec3 p0 = m_.v.d[v];
    double e0 = 0, max0 = 0, len = 0;
    Vec3 g = Vec3::Zero(); // gradient of the sum of squares
    for (int t : vt_[v]) {
      Vec3 gt;
      const double e = energy_gradient_at(m_.tets[t], v, p0, gt);
      if (!std::isfinite(e)) return false;
      e0 += e * e; // squared: the worst tets dominate
      max0 = std::max(max0, e);
      g += 2 * e * gt;
      for (int x : m_.tets[t]) len += (m_.v.d[x] - p0).norm();
    }
    len /= 3.0 * static_cast<double>(vt_[v].size());
    if (!(len > 0)) return false;
    auto sum_at = [&](const Vec3& p, double* mx) {
      double s = 0, m = 0;
      for (int t : vt_[v]) {
        const double e = energy_at(m_.tets[t], v, p);
        s += e * e;
        m = std::max(m, e);
      }
      if (mx) *mx = m;
      return s;
    };
    if (!g.allFinite() || g.norm() == 0) return false;
    const Vec3 dir = -g.normalized();
    for (double step = 0.25 * len; step > 1e-4 * len; step *= 0.5) {
      const Vec3 p = p0 + step * dir;
      double mx;
      const double s = sum_at(p, &mx);
      if (!(s < e0) || !(mx <= max0)) continue;
      if (!star_positive_at(v, p)) continue;
      move(v, p);
      ++stats_.smooths;
      return true;
    }
    return false;
  }

  // The compass search of smooth_max(); see descend_max() for `goal`.
  bool compass_search(int v, double goal = std::numeric_limits<double>::infinity()) {
    if (m_.frozen[v] || pinned(v) || !m_.v.exact[v] || vt_[v].empty()) return false;
    Vec3 p = m_.v.d[v];
    std::vector<Tet> star;
    for (int t : vt_[v]) star.push_back(m_.tets[t]);
    const double before = max_energy_at(star, v, p, nullptr);
    const double after = descend_max(star, v, p, [&](const Vec3& q) { return star_positive_at(v, q); }, goal);
    if (!(after < before)) return false;
    move(v, p);
    ++stats_.smooths;
    return true;
  }
  double max_energy_at(const std::vector<Tet>& tets, int v, const Vec3& q, int* worst) const {
    double m = 0;
    for (int i = 0; i < static_cast<int>(tets.size()); ++i) {
      const double e = energy_at(tets[i], v, q);
      if (e > m) {
        m = e;
        if (worst) *worst = i;
      }
    }
    return m;
  }
  // Compass search, with the worst tet's descent direction tried first, for
  // a position p of v in `tets` (all holding v) with a lower worst energy;
  // valid(q) must hold at every position taken. Returns the worst energy at
  // the final p. With a `goal`, gives up early when that looks out of reach.
  template <class Valid>
  double descend_max(const std::vector<Tet>& tets, int v, Vec3& p, Valid valid,
                     double goal = std::numeric_limits<double>::infinity()) const {
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

  ExactTetMesh m_;
  FillStats& stats_;
  double coarsen_energy_;  // FillOptions::coarsen_energy
  double max_edge_length_; // FillOptions::max_edge_length
  bool journaling_ = false;
  std::vector<std::pair<int, bool>> journal_; // (tet, added) of the open transaction
  std::vector<std::pair<int, std::uint64_t>> saved_touched_; // (vertex, touched_ before) in it
  std::vector<std::vector<int>> vt_;
  std::vector<char> alive_;
  mutable std::vector<std::array<int, 4>> across_; // per tet: neighbours found so far (-1: not known)
  mutable std::array<std::vector<std::array<int, 3>>, 3> link_tris_;
  mutable std::array<std::vector<std::array<int, 2>>, 4> link_edges_;
  mutable std::array<std::vector<int>, 4> link_verts_;
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
  std::vector<std::array<int, 2>> boundary_link(int x) const {
    std::vector<std::array<int, 3>> faces;
    for (int t : vt_[x]) {
      const Tet& q = m_.tets[t];
      for (int k = 0; k < 4; ++k) {
        if (q[k] == x) continue;
        std::array<int, 3> f;
        int j = 0;
        for (int i = 0; i < 4; ++i)
          if (i != k) f[j++] = q[i];
        std::sort(f.begin(), f.end());
        faces.push_back(f);
      }
    }
    std::sort(faces.begin(), faces.end());
    std::vector<std::array<int, 2>> out;
    for (std::size_t i = 0; i < faces.size();) {
      std::size_t j = i;
      while (j < faces.size() && faces[j] == faces[i]) ++j;
      if (j - i == 1) {
        std::array<int, 2> e;
        int k = 0;
        for (int y : faces[i])
          if (y != x) e[k++] = y;
        out.push_back(e);
      }
      i = j;
    }
    return out;
  }
  // With the virtual vertex w joined to the boundary: w in lk(u) ∩ lk(v)
  // needs uv on the boundary; a vertex p in both boundary links needs the
  // boundary face (u, v, p); an edge in both would duplicate a face.
  bool boundary_link_condition(int u, int v) const {
    const auto bu = boundary_link(u), bv = boundary_link(v);
    if (bu.empty() || bv.empty()) return true; // one is interior: no w in both
    std::vector<int> pu, pv, puv;
    for (const auto& e : bu) pu.insert(pu.end(), e.begin(), e.end());
    for (const auto& e : bv) pv.insert(pv.end(), e.begin(), e.end());
    for (const auto& e : bv)
      if (e[0] == u || e[1] == u) puv.push_back(e[0] == u ? e[1] : e[0]);
    if (puv.empty()) return false; // uv is not a boundary edge
    for (auto* l : {&pu, &pv, &puv}) {
      std::sort(l->begin(), l->end());
      l->erase(std::unique(l->begin(), l->end()), l->end());
    }
    std::vector<int> common;
    std::set_intersection(pu.begin(), pu.end(), pv.begin(), pv.end(), std::back_inserter(common));
    for (int p : common)
      if (p != u && p != v && !std::binary_search(puv.begin(), puv.end(), p)) return false;
    auto su = bu, sv = bv;
    std::sort(su.begin(), su.end());
    std::sort(sv.begin(), sv.end());
    std::vector<std::array<int, 2>> ce;
    std::set_intersection(su.begin(), su.end(), sv.begin(), sv.end(), std::back_inserter(ce));
    return ce.empty();
  }

  // Whether a new edge (a, b) would break the sizing bound.
  bool too_long(int a, int b) const {
    return max_edge_length_ > 0 && (m_.v.d[a] - m_.v.d[b]).norm() > max_edge_length_;
  }
  bool orient_positive(Tet& t) const { return m_.v.orient(t[0], t[1], t[2], t[3]) > 0; }
  void kill(int t) {
    if (!alive_[t]) throw Error(ExitCode::internal, "volume: optimizer removed a tet twice");
    if (journaling_) journal_.emplace_back(t, false);
    alive_[t] = 0;
    ++clock_;
    for (int x : m_.tets[t]) {
      if (journaling_) saved_touched_.emplace_back(x, touched_[x]);
      touched_[x] = clock_;
      auto& l = vt_[x];
      l.erase(std::find(l.begin(), l.end(), t));
    }
  }
  int add(const Tet& t) {
    const int id = num_tets();
    m_.tets.push_back(t);
    alive_.push_back(1);
    across_.push_back({-1, -1, -1, -1});
    energy_.push_back(kStale);
    flip_failed_.push_back(0);
    ++clock_;
    for (int x : t) {
      vt_[x].push_back(id);
      if (journaling_) saved_touched_.emplace_back(x, touched_[x]);
      touched_[x] = clock_;
    }
    if (journaling_) journal_.emplace_back(id, true);
    return id;
  }
  bool edge_exists(int a, int b) const {
    for (int t : vt_[a]) {
      const Tet& q = m_.tets[t];
      if (std::find(q.begin(), q.end(), b) != q.end()) return true;
    }
    return false;
  }
  bool face_exists(int a, int b, int c) const {
    for (int t : vt_[a]) {
      const Tet& q = m_.tets[t];
      if (std::find(q.begin(), q.end(), b) != q.end() && std::find(q.begin(), q.end(), c) != q.end()) return true;
    }
    return false;
  }
  // lk(u) ∩ lk(v) = lk(uv) (v interior, so no virtual boundary vertex).
  bool link_condition(int u, int v) const {
    // Scratch buffers reused across calls (this runs for every collapse).
    auto& [tu, tv, ct] = link_tris_;
    auto& [eu, ev, euv, ce] = link_edges_;
    auto& [pu, pv, puv, cp] = link_verts_;
    auto link = [&](int x, std::vector<std::array<int, 3>>& tris, std::vector<std::array<int, 2>>& edges,
                    std::vector<int>& verts) {
      tris.clear();
      edges.clear();
      verts.clear();
      for (int t : vt_[x]) {
        std::array<int, 3> f;
        int j = 0;
        for (int y : m_.tets[t])
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
    // lk(uv): opposite edges of the tets containing both.
    euv.clear();
    puv.clear();
    for (int t : vt_[v]) {
      const Tet& q = m_.tets[t];
      if (std::find(q.begin(), q.end(), u) == q.end()) continue;
      std::array<int, 2> e;
      int j = 0;
      for (int y : q)
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
    for (int p : cp)
      if (!std::binary_search(puv.begin(), puv.end(), p)) return false;
    return true;
  }
};

// `failed[v]`: the optimizer's clock at v's last failed collapse (0: none);
// v is not retried while its star stays unchanged.
void collapse_pass(Optimizer& o, bool only_rational, std::vector<std::uint64_t>& failed) {
  auto& m = o.mesh();
  failed.resize(m.v.size(), 0);
  for (int v = 0; v < m.v.size(); ++v) {
    if (m.frozen[v] || o.star(v).empty()) continue;
    const bool rational = !m.v.exact[v];
    if (only_rational && !rational) continue;
    if (o.unchanged_since(v, failed[v])) continue;
    auto nb = o.neighbours(v);
    std::sort(nb.begin(), nb.end(), [&](int a, int b) {
      return (m.v.d[a] - m.v.d[v]).squaredNorm() < (m.v.d[b] - m.v.d[v]).squaredNorm();
    });
    if (std::none_of(nb.begin(), nb.end(), [&](int u) { return o.collapse(v, u, rational ? Optimizer::Keep::positivity : Optimizer::Keep::quality); })) failed[v] = o.clock();
  }
}

// Removes the Steiner vertices on the surface (sweeps until none can go);
// returns how many are left.
std::size_t surface_steiner_pass(Optimizer& o) {
  auto& m = o.mesh();
  std::size_t left = 0;
  for (bool progress = true; progress;) {
    progress = false;
    left = 0;
    for (const auto& st : m.on_surface) {
      if (!o.pinned(st.vertex)) continue;
      // the allowed target giving the best worst tet
      int best = -1;
      double best_cost = std::numeric_limits<double>::infinity();
      for (int u : st.targets) {
        if (o.star(u).empty()) continue;
        const double c = o.surface_collapse_cost(st.vertex, u);
        if (c < best_cost) {
          best_cost = c;
          best = u;
        }
      }
      const bool done = best >= 0 && o.collapse_on_surface(st.vertex, best);
      if (done) {
        progress = true;
      } else {
        ++left;
      }
    }
  }
  return left;
}

// Flips on every tet at or above threshold; returns how many were made.
std::size_t flip_pass(Optimizer& o, double threshold) {
  auto& m = o.mesh();
  const int nt = o.num_tets();
  std::size_t flips = 0;
  for (int t = 0; t < nt; ++t) {
    if (!o.alive(t)) continue;
    if (o.tet_energy(t) < threshold || o.flips_known_to_fail(t)) continue;
    const auto q = m.tets[t];
    // The edges' tets, found once: a flip that fails changes nothing (so t
    // is still alive below when none succeeded).
    std::array<std::vector<int>, 6> rings;
    bool done = false;
    for (int i = 0, e = 0; i < 4 && !done; ++i)
      for (int j = i + 1; j < 4 && !done; ++j, ++e) {
        rings[e] = o.edge_ring(q[i], q[j]);
        done = o.flip_32(q[i], q[j], rings[e]);
      }
    for (int k = 0; k < 4 && !done; ++k) done = o.flip_23(t, k);
    for (int i = 0, e = 0; i < 4 && !done; ++i)
      for (int j = i + 1; j < 4 && !done; ++j, ++e) done = o.remove_edge(q[i], q[j], rings[e]);
    if (!done) o.mark_flips_failed(t);
    flips += done;
  }
  return flips;
}

// 3-2 flips (alone or after an edge removal) wherever they keep the energy
// bound: each removes a tet.
std::size_t flip_32_pass(Optimizer& o) {
  auto& m = o.mesh();
  const std::size_t before = o.mesh().tets.size();
  std::size_t flips = 0;
  for (std::size_t t = 0; t < before; ++t) {
    if (!o.alive(static_cast<int>(t))) continue;
    const auto q = m.tets[t];
    bool done = false;
    for (int i = 0; i < 4 && !done; ++i)
      for (int j = i + 1; j < 4 && !done; ++j) done = o.flip_32(q[i], q[j]) || o.remove_edge_then_32(q[i], q[j]);
    flips += done;
  }
  return flips;
}

// Calls fix(t) on each tet of `bad` still alive and at or above `above`;
// whether any call changed the mesh.
template <class Fix>
bool on_still_bad(Optimizer& o, const std::vector<int>& bad, double above, Fix fix) {
  bool any = false;
  for (int t : bad)
    if (o.alive(t) && o.tet_energy(t) >= above) any |= fix(t);
  return any;
}
// Tries fix(x) on the free, rounded corners of t until one succeeds.
template <class Fix>
bool on_free_corner(Optimizer& o, int t, Fix fix) {
  auto& m = o.mesh();
  for (int x : std::array<int, 4>(m.tets[t]))
    if (!m.frozen[x] && m.v.exact[x] && fix(x)) return true;
  return false;
}

// Where smoothing is blocked (a free vertex hemmed in by its star, e.g.
// over a sliver input face), removing that vertex may not be: each tet of
// `bad` still above `threshold` tries to collapse one of its free vertices
// so that the vertex's star gets a strictly lower worst tet.
bool remove_blocked_vertices(Optimizer& o, const std::vector<int>& bad, double threshold) {
  return on_still_bad(o, bad, threshold, [&](int t) {
    return on_free_corner(o, t, [&](int x) {
      const auto nb = o.neighbours(x);
      return std::any_of(nb.begin(), nb.end(), [&](int u) { return o.collapse(x, u, Optimizer::Keep::lower_max); });
    });
  });
}

// Tets of `bad` still above `above`: a free corner moves to where the tet
// alone would be best (or part of the way), through a cavity where its star
// blocks the straight move.
constexpr double kFractions[] = {1.0, 0.5, 0.25};
bool relocate_worst(Optimizer& o, const std::vector<int>& bad, double above) {
  return on_still_bad(o, bad, above, [&](int t) {
    return on_free_corner(o, t, [&](int x) {
      const Vec3 p0 = o.mesh().v.d[x], target = o.best_corner(t, x);
      return std::any_of(std::begin(kFractions), std::end(kFractions),
                         [&](double f) { return o.relocate_through_cavity(x, p0 + f * (target - p0)); });
    });
  });
}

// Tets of `bad` still above `above`: a new vertex, Delaunay-refinement
// style, at the first of these that improves: the circumcentre; for each of
// the tet's faces on the boundary, where a regular tet on that face would
// have its apex (a flat tet between two boundary faces, as on a fillet,
// needs a point well inside); the centroid.
bool insert_worst(Optimizer& o, const std::vector<int>& bad, double above) {
  return on_still_bad(o, bad, above, [&](int t) {
    const auto& m = o.mesh();
    std::array<Vec3, 4> x;
    for (int k = 0; k < 4; ++k) x[k] = m.v.d[m.tets[t][k]];
    std::vector<Vec3> candidates{circumcentre(x[0], x[1], x[2], x[3])};
    for (int k = 0; k < 4; ++k) {
      if (o.across(t, k) >= 0) continue;
      const Vec3 &f0 = x[(k + 1) % 4], &f1 = x[(k + 2) % 4], &f2 = x[(k + 3) % 4];
      Vec3 n = (f1 - f0).cross(f2 - f0).normalized();
      if (n.dot(x[k] - f0) < 0) n = -n; // towards the tet, i.e. inside
      const double edge = ((f1 - f0).norm() + (f2 - f1).norm() + (f0 - f2).norm()) / 3;
      for (double depth : kFractions) // nearer, where the surface curves in
        candidates.push_back((f0 + f1 + f2) / 3 + depth * std::sqrt(2.0 / 3.0) * edge * n);
    }
    candidates.push_back(0.25 * (x[0] + x[1] + x[2] + x[3]));
    return std::any_of(candidates.begin(), candidates.end(),
                       [&](const Vec3& p) { return p.allFinite() && o.alive(t) && o.insert_vertex(t, p); });
  });
}

// The worst tets that are left (also those on frozen vertices only) above
// `above`: a new vertex on one of their interior edges, else inside them.
bool split_worst(Optimizer& o, const std::vector<int>& bad, double above) {
  return on_still_bad(o, bad, above, [&](int t) {
    // An undone edge split re-creates t under a new id: t is split itself
    // only when it has no interior edge.
    const auto q = o.mesh().tets[t];
    bool interior = false;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (const auto ring = o.interior_ring(q[i], q[j]); !ring.empty()) {
          interior = true;
          if (o.split_edge(q[i], q[j], ring)) return true;
        }
    return !interior && o.split_tet(t);
  });
}

// Worst-tet passes: flips, then smoothing, removal, relocation and (with
// `splits`) new vertices around the tets whose energy is within `focus` of
// the current maximum over tets with a free vertex (those smoothing can
// change; over all tets while none has one). Stops when a pass lowers
// neither that maximum nor the overall one, or once every tet is below
// kGoodMaxEnergy (more passes there only polish the bulk: cad_fillet3 spent
// 2 s taking 3.2 to 2.8).
// With `insert` (the Delaunay fill, whose bad tets mostly have no free
// vertex), the passes aim at every tet within `focus` of the maximum, or
// above focus × kBroadEnergy; a tet that several passes could not improve
// is set aside for the others; they stop on the same kind of signs of
// diminishing returns, or when the tries exceed the tet count.
constexpr double kGoodMaxEnergy = 3.5;
constexpr double kBroadEnergy = 12;
// Within 1 % of the least energy its boundary faces allow, a tet is left
// alone, and once the maximum is, the passes stop (bunny: 8 passes, a third
// of its run, took 5.48 to 5.47 over a floor of 5.46).
constexpr double kNearFloor = 1.01;
// The least energy tet t can have while its boundary faces (input or box
// faces, which stay) stay: 0 without one.
double boundary_floor(Optimizer& o, int t) {
  const Tet& q = o.mesh().tets[t];
  const auto& d = o.mesh().v.d;
  double floor = 0;
  for (int k = 0; k < 4; ++k)
    if (o.across(t, k) < 0)
      floor = std::max(floor, least_amips_on_face(d[q[(k + 1) % 4]], d[q[(k + 2) % 4]], d[q[(k + 3) % 4]]));
  return floor;
}
struct WorstPassPlan {
  int passes = 8;
  double focus = 0.5;
  bool splits = true;  // edge or tet splits
  bool insert = false; // Delaunay-style insertions before the splits
  double min_gain = 0;  // see worst_pass
};
void worst_pass(Optimizer& o, const WorstPassPlan& plan) {
  auto& m = o.mesh();
  auto has_free_vertex = [&](int t) {
    return std::any_of(m.tets[t].begin(), m.tets[t].end(), [&](int x) { return !m.frozen[x]; });
  };
  // With insertions, a tet that kMaxTries whole passes left above their
  // threshold is set aside, so that the passes go on down the tail behind
  // it (known by its corners: an undone operation re-creates a tet under a
  // new id).
  constexpr int kMaxTries = 3;
  std::map<Tet, int> failures;
  std::set<Tet> set_aside;
  constexpr int kPolishPasses = 3;
  int polish = 0;
  auto corners = [&](int t) {
    Tet q = m.tets[t];
    std::sort(q.begin(), q.end());
    return q;
  };
  int stalled = 0;
  std::size_t tried_tets = 0;
  const std::size_t budget = o.num_alive();
  double best_open = std::numeric_limits<double>::infinity();
  double previous = std::numeric_limits<double>::infinity(), previous_all = previous;
  double floor = 0; // no mesh with these boundary faces has a lower maximum
  for (int t = 0; t < o.num_tets(); ++t)
    if (o.alive(t)) floor = std::max(floor, boundary_floor(o, t));
  for (int pass = 0; pass < plan.passes; ++pass) {
    // mx: over tets with a free vertex (those smoothing can change);
    // mx_open: over all, those set aside excepted.
    double mx = 0, mx_all = 0, mx_open = 0;
    std::vector<char> stuck(o.num_tets(), 0);
    for (int t = 0; t < o.num_tets(); ++t)
      if (o.alive(t)) {
        const double e = o.tet_energy(t);
        mx_all = std::max(mx_all, e);
        stuck[t] = e >= 2.0 && !set_aside.empty() && set_aside.count(corners(t));
        if (stuck[t]) continue;
        mx_open = std::max(mx_open, e);
        if (has_free_vertex(t)) mx = std::max(mx, e);
      }
    if (mx_all <= kNearFloor * floor) break;
    if (plan.insert) {
      // A budget of as many tries as the mesh has tets: where thousands of
      // tets stay bad (needle input faces) passes would go on for long.
      if (mx_all < kGoodMaxEnergy || tried_tets > budget) break;
      stalled = mx_open < best_open ? 0 : stalled + 1;
      best_open = std::min(best_open, mx_open);
      // Also done after kPolishPasses passes with the rest well below the
      // tets set aside (polishing it lowers the maximum only by the way), or
      // once a pass took a reasonable maximum down by less than min_gain.
      polish = mx_open < plan.focus * mx_all ? polish + 1 : 0;
      // (Another chance for the tets set aside, in their new surroundings,
      // lowered the maximum by 0.3 % on nefertiti and on none of the other
      // 17 models that take this path.)
      if (stalled == 3 || mx_open < kGoodMaxEnergy || polish > kPolishPasses ||
          (mx_all < 1.5 * kGoodMaxEnergy && mx_all > (1 - plan.min_gain) * previous_all))
        break;
    } else {
      if (!(mx < previous) && !(mx_all < previous_all)) break;
      if (mx_all < kGoodMaxEnergy) break;
      if (mx_all < 1.5 * kGoodMaxEnergy && mx_all > (1 - plan.min_gain) * previous_all) break;
    }
    previous = mx;
    previous_all = mx_all;
    // Insertions reach tets without a free vertex too: they aim at all, and
    // at every tet above kBroadEnergy at once.
    const double target = plan.insert ? std::min(mx_open, kBroadEnergy) : mx > 0 ? mx : mx_open;
    const double threshold = std::max(2.0, plan.focus * target);
    std::vector<int> bad;
    for (int t = 0; t < o.num_tets(); ++t)
      if (o.alive(t) && o.tet_energy(t) >= threshold && !stuck[t] &&
          o.tet_energy(t) > kNearFloor * boundary_floor(o, t))
        bad.push_back(t);
    std::set<Tet> tried;
    if (plan.insert)
      for (int t : bad) tried.insert(corners(t));
    tried_tets += bad.size();
    bool any = flip_pass(o, threshold) > 0;
    for (int t : bad)
      if (o.alive(t))
        for (int x : std::array<int, 4>(m.tets[t])) any |= o.smooth_max(x);
    any |= remove_blocked_vertices(o, bad, threshold);
    const double above = plan.insert ? threshold : std::max(threshold, plan.focus * mx_open);
    any |= relocate_worst(o, bad, above);
    if (plan.splits && plan.insert) any |= insert_worst(o, bad, above);
    if (plan.splits) any |= split_worst(o, bad, above);
    for (int t = 0; t < o.num_tets() && plan.insert; ++t) {
      if (!o.alive(t) || o.tet_energy(t) < above) continue;
      const Tet c = corners(t);
      if (tried.count(c) && ++failures[c] == kMaxTries) {
        set_aside.insert(c);
        any = true;
      }
    }
    logger().debug("volume: worst pass {}: max {:.4g}, {:.4g} with a free vertex, {:.4g} not set aside ({}); {} tets "
                   "above {:.4g}, changed: {}",
                   pass, mx_all, mx, mx_open, set_aside.size(), bad.size(), threshold, any);
    if (!any) break;
  }
}

// Whether the tet of highest energy has no free vertex.
bool worst_is_frozen(Optimizer& o) {
  const auto& m = o.mesh();
  int worst = -1;
  for (int t = 0; t < o.num_tets(); ++t)
    if (o.alive(t) && (worst < 0 || o.tet_energy(t) > o.tet_energy(worst))) worst = t;
  return worst >= 0 && std::all_of(m.tets[worst].begin(), m.tets[worst].end(), [&](int x) { return m.frozen[x]; });
}

void smooth_pass(Optimizer& o) {
  auto& m = o.mesh();
  for (int v = 0; v < m.v.size(); ++v)
    if (m.v.exact[v]) o.smooth(v);
}

} // namespace

mesh::LinearTetMesh round_and_optimize(ExactTetMesh&& m, int num_keep, const FillOptions& options, FillStats& stats) {
  Optimizer o(std::move(m), stats, options);
  std::vector<std::uint64_t> collapse_failed;
  auto tic = std::chrono::steady_clock::now();
  auto phase = [&](const char* name) {
    const auto now = std::chrono::steady_clock::now();
    logger().debug("volume: optimize phase {}: {:.3f} s, {} tets", name, std::chrono::duration<double>(now - tic).count(), o.num_alive());
    tic = now;
  };
  std::size_t on_surface = surface_steiner_pass(o);
  std::size_t left = o.round_pass();
  stats.unrounded_after_first_pass = left;
  phase("round");
  // Without a free vertex (the Delaunay fill: none but the few centres of
  // its cones), collapses and smoothing have next to nothing to move: one
  // round of flips, then the worst-tet passes insert.
  const auto& fr = o.mesh().frozen;
  const bool mostly_frozen = stats.direct || std::find(fr.begin(), fr.end(), 0) == fr.end();
  const int rounds = mostly_frozen ? std::min(options.optimize_rounds, 1) : options.optimize_rounds;
  for (int round = 0; round < rounds; ++round) {
    collapse_pass(o, false, collapse_failed);
    phase("collapse");
    flip_pass(o, 3.0);
    phase("flip");
    smooth_pass(o);
    phase("smooth");
    left = o.round_pass();
    logger().debug("volume: optimize round {}: {} collapses, {} flips, {} smooths, {} unrounded", round,
                   stats.collapses, stats.flips, stats.smooths, left);
  }
  // Coarsening: collapses and 3-2 flips within the energy bound until
  // neither removes a tet.
  for (int round = 0; options.coarsen_energy > 0 && round < 10; ++round) {
    const std::size_t collapses = stats.collapses;
    collapse_pass(o, false, collapse_failed);
    phase("coarsen collapse");
    const std::size_t flips = flip_32_pass(o);
    phase("coarsen flip");
    smooth_pass(o);
    phase("coarsen smooth");
    if (stats.collapses == collapses && flips == 0) break;
  }
  // A coarsening fill keeps its vertex count down: no splits there. A fill
  // that started without a free vertex (the Delaunay fill: a bulk of flat
  // tets between surface vertices) needs Steiner points, as in Delaunay
  // refinement: more passes, each on the tets near the current worst.
  WorstPassPlan plan;
  plan.splits = options.coarsen_energy <= 0;
  if (mostly_frozen) {
    plan.passes = 30;
    plan.focus = 0.75;
    plan.min_gain = 0.03;
    plan.insert = true;
  }
  if (options.optimize_rounds > 0) worst_pass(o, plan);
  phase("worst");
  // The collapses of a layered fill can leave its worst tet between four
  // frozen vertices, where only flips and insertions reach (cheese_genus133:
  // 1014 there, 330 elsewhere): a few passes with insertions, as above.
  if (options.optimize_rounds > 0 && !plan.insert && plan.splits && worst_is_frozen(o)) {
    plan.passes = 3;
    plan.focus = 0.75;
    plan.insert = true;
    worst_pass(o, plan);
    phase("worst with insertions");
  }
  // Whatever is still rational: remove it or move it to a double position.
  for (int attempt = 0; attempt < 20 && left > 0; ++attempt) {
    collapse_pass(o, true, collapse_failed);
    auto& mm = o.mesh();
    for (int v = 0; v < mm.v.size(); ++v)
      if (!mm.v.exact[v] && !o.star(v).empty()) o.relocate(v);
    left = o.round_pass();
  }
  if (on_surface > 0) on_surface = surface_steiner_pass(o);
  if (on_surface > 0)
    throw Error(ExitCode::internal,
                fmt::format("volume: {} Steiner vertices on pinched surface edges/faces could not be removed", on_surface));
  left = o.count_rational();
  if (left > 0) throw Error(ExitCode::internal, fmt::format("volume: {} vertices could not be rounded", left));
  auto out = o.extract(num_keep);
  // Reported in highorder/quality.hpp's convention: 3 x the fill's energy.
  double sum = 0, mx = 0, min_sj = out.tets.empty() ? 0 : std::numeric_limits<double>::infinity();
  for (const auto& t : out.tets) {
    const auto &a = out.vertices[t[0]], &b = out.vertices[t[1]], &c = out.vertices[t[2]], &d = out.vertices[t[3]];
    const double e = kReportedAmipsPerEnergy * tet_amips(a, b, c, d);
    sum += e;
    mx = std::max(mx, e);
    Eigen::Matrix3d j;
    j << b - a, c - a, d - a;
    min_sj = std::min(min_sj, highorder::scaled_jacobian(j));
  }
  stats.max_amips = mx;
  stats.min_scaled_jacobian = min_sj;
  stats.mean_amips = out.tets.empty() ? 0 : sum / static_cast<double>(out.tets.size());
  return out;
}

} // namespace curvetet::volume::exact

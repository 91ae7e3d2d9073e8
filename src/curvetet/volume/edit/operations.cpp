#include "curvetet/volume/edit/operations.hpp"

#include "curvetet/highorder/node_ordering.hpp"

#include <algorithm>
#include <array>
#include <functional>

namespace curvetet::volume::edit {
namespace {

using Tri = std::array<int, 3>;

template <class T>
void unique_sort(std::vector<T>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

bool has_corner(const Corners& c, int v) { return std::find(c.begin(), c.end(), v) != c.end(); }

// Whether (p0, p1, p2, p3) is an even permutation of c.
bool even_permutation(const Corners& c, const Corners& p) {
  std::array<int, 4> index{};
  for (int i = 0; i < 4; ++i) index[i] = static_cast<int>(std::find(c.begin(), c.end(), p[i]) - c.begin());
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += index[i] > index[j];
  return inversions % 2 == 0;
}

// Every triangulation of the convex polygon 0..n-1 (as index triples, each
// in polygon order).
void triangulations(int lo, int hi, std::vector<std::vector<Tri>>& out) {
  out.clear();
  if (hi - lo < 2) {
    out.emplace_back();
    return;
  }
  for (int m = lo + 1; m < hi; ++m) {
    std::vector<std::vector<Tri>> left, right;
    triangulations(lo, m, left);
    triangulations(m, hi, right);
    for (const auto& l : left)
      for (const auto& r : right) {
        std::vector<Tri> t = l;
        t.insert(t.end(), r.begin(), r.end());
        t.push_back({lo, m, hi});
        out.push_back(std::move(t));
      }
  }
}

const std::vector<std::vector<Tri>>& ring_triangulations(int n) {
  static const auto table = [] {
    std::array<std::vector<std::vector<Tri>>, kMaxRing + 1> t;
    for (int k = 3; k <= kMaxRing; ++k) triangulations(0, k - 1, t[k]);
    return t;
  }();
  return table[n];
}

} // namespace

bool collapse(const TetEditor& e, int a, int b, Proposal& out, Reject* why) {
  out = {};
  if (e.frozen(a)) return *why = Reject::frozen, false;
  const auto& star = e.tets_of(a);
  if (star.empty()) return *why = Reject::link_condition, false;
  const int region = e.tag(star.front());
  for (int t : star) {
    if (e.tag(t) != region) return *why = Reject::region, false;
    if (has_corner(e.corners(t), b)) out.kill.push_back(t);
  }
  if (out.kill.empty()) return *why = Reject::link_condition, false; // not an edge
  // With b on the boundary, its link closes through a vertex at infinity;
  // a is interior, so lk(a) never holds it: the plain condition suffices.
  TetStars::LinkBuffers buffers;
  if (!e.stars().link_condition(b, a, buffers, [&](int t) { return e.tag(t) == region; }))
    return *why = Reject::link_condition, false;
  for (int t : star) {
    Corners c = e.corners(t);
    if (has_corner(c, b)) continue;
    out.kill.push_back(t);
    std::replace(c.begin(), c.end(), a, b);
    out.add.push_back({c, region});
  }
  return true;
}

// The tets on edge ab, if it is interior (closed ring) and in one region.
bool interior_edge_shell(const TetEditor& e, int a, int b, std::vector<int>& shell, Reject* why) {
  shell.clear();
  for (int t : e.tets_of(a))
    if (has_corner(e.corners(t), b)) shell.push_back(t);
  if (shell.size() < 3) return *why = Reject::boundary_edge, false;
  for (int t : shell)
    if (e.tag(t) != e.tag(shell.front())) return *why = Reject::region, false;
  for (int t : shell) {
    const Corners& c = e.corners(t);
    for (const auto& f : highorder::kTetFaces) {
      const int x = c[f[0]], y = c[f[1]], z = c[f[2]];
      const bool on_edge = (x == a || y == a || z == a) && (x == b || y == b || z == b);
      if (on_edge && e.is_boundary_face(x, y, z)) return *why = Reject::boundary_edge, false;
    }
  }
  return true;
}

bool split(const TetEditor& e, int a, int b, Proposal& out, Reject* why) {
  out = {};
  if (!interior_edge_shell(e, a, b, out.kill, why)) return false;
  out.adds_vertex = true;
  out.new_vertex = 0.5 * (e.position(a) + e.position(b));
  for (int t : out.kill) {
    Corners c = e.corners(t), d = c;
    std::replace(c.begin(), c.end(), a, kNewVertex);
    std::replace(d.begin(), d.end(), b, kNewVertex);
    out.add.push_back({c, e.tag(t)});
    out.add.push_back({d, e.tag(t)});
  }
  return true;
}

bool remove_edge(const TetEditor& e, int a, int b, std::vector<Proposal>& out, Reject* why) {
  out.clear();
  std::vector<int> shell;
  if (!interior_edge_shell(e, a, b, shell, why)) return false;
  const int n = static_cast<int>(shell.size());
  if (n > kMaxRing) return *why = Reject::boundary_edge, false;
  const int region = e.tag(shell.front());
  // Ring: each tet, ordered (a, b, u, w) positively, links u -> w.
  std::vector<std::pair<int, int>> next;
  for (int t : shell) {
    if (e.tag(t) != region) return *why = Reject::region, false;
    const Corners& c = e.corners(t);
    int u = -1, w = -1;
    for (int v : c)
      if (v != a && v != b) (u < 0 ? u : w) = v;
    if (!even_permutation(c, {a, b, u, w})) std::swap(u, w);
    next.emplace_back(u, w);
  }
  std::vector<int> ring{next.front().first};
  for (int k = 0; k < n; ++k) {
    const auto it = std::find_if(next.begin(), next.end(), [&](const auto& p) { return p.first == ring.back(); });
    if (it == next.end()) return *why = Reject::boundary_edge, false; // open ring: a boundary edge
    ring.push_back(it->second);
  }
  if (ring.back() != ring.front()) return *why = Reject::boundary_edge, false;
  ring.pop_back();
  std::vector<int> distinct = ring;
  unique_sort(distinct);
  if (static_cast<int>(distinct.size()) != n) return *why = Reject::boundary_edge, false;
  if (n == 3 && e.has_face(ring[0], ring[1], ring[2])) return *why = Reject::duplicate_entity, false;
  // Ring edges exist; diagonals must not.
  std::vector<std::vector<char>> diagonal_exists(n, std::vector<char>(n, 0));
  for (int i = 0; i < n; ++i)
    for (int j = i + 2; j < n; ++j)
      if (!(i == 0 && j == n - 1)) diagonal_exists[i][j] = e.has_edge(ring[i], ring[j]);
  for (const auto& tris : ring_triangulations(n)) {
    bool ok = true;
    for (const Tri& t : tris)
      for (int k = 0; k < 3; ++k) {
        const int i = std::min(t[k], t[(k + 1) % 3]), j = std::max(t[k], t[(k + 1) % 3]);
        if (j - i >= 2 && !(i == 0 && j == n - 1) && diagonal_exists[i][j]) ok = false;
      }
    if (!ok) continue;
    Proposal p;
    p.kill = shell;
    for (const Tri& t : tris) {
      const int x = ring[t[0]], y = ring[t[1]], z = ring[t[2]];
      p.add.push_back({{x, y, z, b}, region});
      p.add.push_back({{y, x, z, a}, region});
    }
    out.push_back(std::move(p));
  }
  if (out.empty()) return *why = Reject::duplicate_entity, false;
  return true;
}

bool flip_face(const TetEditor& e, int t, int face, Proposal& out, Reject* why) {
  out = {};
  const Corners& c = e.corners(t);
  const int a = c[face];
  const int x = c[highorder::kTetFaces[face][0]], y = c[highorder::kTetFaces[face][1]],
            z = c[highorder::kTetFaces[face][2]]; // outward from t
  if (e.is_boundary_face(x, y, z)) return *why = Reject::boundary_edge, false;
  int other = -1;
  for (int s : e.tets_of(x))
    if (s != t && has_corner(e.corners(s), y) && has_corner(e.corners(s), z)) other = s;
  if (other < 0) return *why = Reject::boundary_edge, false;
  if (e.tag(other) != e.tag(t)) return *why = Reject::region, false;
  int b = -1;
  for (int v : e.corners(other))
    if (v != x && v != y && v != z) b = v;
  if (e.has_edge(a, b)) return *why = Reject::duplicate_entity, false;
  out.kill = {t, other};
  const int region = e.tag(t);
  out.add = {{{x, y, a, b}, region}, {{y, z, a, b}, region}, {{z, x, a, b}, region}};
  return true;
}

} // namespace curvetet::volume::edit

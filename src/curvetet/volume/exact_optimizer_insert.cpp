#include "curvetet/volume/exact_optimizer.hpp"

#include "curvetet/geometry/predicates.hpp"
#include "curvetet/volume/mesh_keys.hpp"

#include <algorithm>
#include <vector>

namespace curvetet::volume::exact {

bool Optimizer::split_edge(int a, int b, const std::vector<int>& ring) {
  double old_max = 0;
  for (int t : ring) old_max = std::max(old_max, tet_energy(t));
  const Vec3 p = 0.5 * (m_.v.d[a] + m_.v.d[b]);
  std::vector<Tet> halves;
  for (int t : ring)
    for (int end : {a, b}) {
      Tet h = stars_.corners(t);
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

bool Optimizer::split_tet(int t) {
  const Tet q = stars_.corners(t);
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

bool Optimizer::commit_split(int m, const std::vector<int>& old, const std::vector<Tet>& parts, double old_max) {
  begin_journal();
  for (int t : old) kill(t);
  for (const Tet& h : parts) add(h);
  journaling_ = false;
  compass_search(m, old_max);
  double new_max = 0;
  for (int t : stars_.star(m)) new_max = std::max(new_max, tet_energy(t));
  if (new_max < old_max) {
    ++stats_.splits;
    return true;
  }
  undo_journal();
  return false;
}

bool Optimizer::relocate_through_cavity(int v, const Vec3& target) {
  if (m_.frozen[v] || pinned(v) || !m_.v.exact[v] || stars_.star(v).empty()) return false;
  if (!restar(v, target, stars_.star(v))) return false;
  ++stats_.relocations;
  return true;
}

bool Optimizer::insert_vertex(int from, const Vec3& p) {
  const int holder = locate(from, p);
  if (holder < 0) return false;
  std::vector<int> cavity{holder};
  ++cavity_stamp_;
  cavity_mark_.resize(stars_.num_slots(), 0);
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

int Optimizer::locate(int from, const Vec3& p) const {
  int t = from;
  for (int steps = 0; steps < 1000; ++steps) {
    const Tet& q = stars_.corners(t);
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

int Optimizer::orient_with(const Tet& c, const Vec3& p) const {
  Vec3 x[4];
  for (int k = 0; k < 4; ++k) x[k] = c[k] < 0 ? p : m_.v.d[c[k]];
  return geometry::orient3d(x[0], x[1], x[2], x[3]);
}

bool Optimizer::in_circumsphere(int t, const Vec3& p) const {
  const Tet& q = stars_.corners(t);
  const Vec3 centre = circumcentre(m_.v.d[q[0]], m_.v.d[q[1]], m_.v.d[q[2]], m_.v.d[q[3]]);
  return centre.allFinite() && (p - centre).squaredNorm() < (m_.v.d[q[0]] - centre).squaredNorm();
}

bool Optimizer::restar(int v, const Vec3& target, const std::vector<int>& seed, bool search) {
  std::vector<int> cavity = seed;
  ++cavity_stamp_;
  cavity_mark_.resize(stars_.num_slots(), 0);
  for (int t : cavity) cavity_mark_[t] = cavity_stamp_;
  // Boundary faces as (tet, corner opposite): a new tet is that tet with v
  // at target in place of the corner.
  // Grow (each tet's faces are looked at once: a face seen strictly stays
  // so), then collect the faces still on the boundary.
  // (tet, corner, tet across): the across is kept for the final filter.
  std::vector<std::array<int, 3>> seen;
  for (std::size_t i = 0; i < cavity.size(); ++i) {
    const Tet& q = stars_.corners(cavity[i]);
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
    Tet c = stars_.corners(t);
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

bool Optimizer::bounds_sphere(const std::vector<std::pair<int, int>>& faces) const {
  std::vector<std::array<int, 3>> tris;
  for (auto [t, k] : faces) {
    std::array<int, 3> f;
    for (int i = 0, j = 0; i < 4; ++i)
      if (i != k) f[j++] = stars_.corners(t)[i];
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

} // namespace curvetet::volume::exact

#include "curvetet/volume/exact_optimizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

namespace curvetet::volume::exact {

namespace {
// Tet q with its corner v at u instead.
Tet moved(Tet q, int v, int u) {
  std::replace(q.begin(), q.end(), v, u);
  return q;
}
} // namespace

bool Optimizer::surface_collapse_allowed(int v, int u, std::vector<int>& removed, double* worst,
                                         FillReject* why) const {
  const auto fail = [&](FillReject r) {
    if (why) *why = r;
    return false;
  };
  removed.clear();
  std::vector<Tet> added;
  for (int t : stars_.star(v)) {
    const Tet& q = stars_.corners(t);
    if (std::find(q.begin(), q.end(), u) != q.end())
      removed.push_back(t);
    else
      added.push_back(moved(q, v, u));
  }
  if (const auto broken = broken_invariant(added, NewTetRule{})) return fail(*broken); // positivity
  if (worst)
    for (const Tet& n : added) *worst = std::max(*worst, energy(n));
  if (removed.empty()) return fail(FillReject::topology);
  if (!link_condition(u, v) || !boundary_link_condition(u, v)) return fail(FillReject::link_condition);
  return true;
}

double Optimizer::surface_collapse_cost(int v, int u) const {
  std::vector<int> removed;
  double worst = 0;
  return surface_collapse_allowed(v, u, removed, &worst) ? worst : std::numeric_limits<double>::infinity();
}

bool Optimizer::collapse_on_surface(int v, int u) {
  std::vector<int> removed;
  FillReject why{};
  if (!surface_collapse_allowed(v, u, removed, nullptr, &why)) return reject(why);
  merge(v, u, removed);
  pinned_[v] = 0;
  ++stats_.collapses;
  return true;
}

bool Optimizer::collapse(int v, int u, Keep keep) {
  if (m_.frozen[v] || pinned(v) || u == v) return reject(FillReject::frozen);
  double old_max = 0;
  for (int t : stars_.star(v)) old_max = std::max(old_max, tet_energy(t));
  std::vector<int> removed;
  std::vector<Tet> added;
  for (int t : stars_.star(v)) {
    const Tet& q = stars_.corners(t);
    if (std::find(q.begin(), q.end(), u) != q.end())
      removed.push_back(t);
    else
      added.push_back(moved(q, v, u));
  }
  NewTetRule rule;
  if (keep == Keep::quality) {
    rule.max_energy = std::max(old_max, coarsen_energy_);
    rule.frozen_limit = true;
    rule.sizing_from = u;
  } else if (keep == Keep::lower_max) {
    rule.max_energy = old_max;
    rule.strict = true;
    rule.energy_reason = FillReject::no_gain;
  }
  if (const auto why = broken_invariant(added, rule)) return reject(*why);
  if (removed.empty()) return reject(FillReject::topology); // not an edge
  if (!link_condition(u, v)) return reject(FillReject::link_condition);
  merge(v, u, removed);
  ++stats_.collapses;
  return true;
}

std::optional<FillReject> Optimizer::broken_invariant(const std::vector<Tet>& tets, const NewTetRule& rule) const {
  const bool needs_energy = std::isfinite(rule.max_energy) || rule.frozen_limit;
  std::vector<double> e(needs_energy ? tets.size() : 0);
  for (std::size_t i = 0; i < e.size(); ++i) {
    e[i] = energy(tets[i]);
    if (!(rule.strict ? e[i] < rule.max_energy : e[i] <= rule.max_energy)) return rule.energy_reason;
  }
  if (rule.frozen_limit)
    for (std::size_t i = 0; i < tets.size(); ++i) {
      const Tet& n = tets[i];
      if (e[i] > std::max(kFrozenTetLimit, coarsen_energy_) && m_.frozen[n[0]] && m_.frozen[n[1]] &&
          m_.frozen[n[2]] && m_.frozen[n[3]])
        return FillReject::frozen_tet_energy;
    }
  if (rule.sizing_from >= 0)
    for (const Tet& n : tets)
      for (int x : n)
        if (x != rule.sizing_from && too_long(rule.sizing_from, x) && !edge_exists(rule.sizing_from, x))
          return FillReject::sizing;
  for (const Tet& n : tets)
    if (m_.v.orient(n[0], n[1], n[2], n[3]) <= 0) return FillReject::positivity;
  return std::nullopt;
}

void Optimizer::merge(int v, int u, const std::vector<int>& removed) {
  for (int t : removed) kill(t);
  ++clock_;
  for (int t : std::vector<int>(stars_.star(v))) {
    across_[t] = {-1, -1, -1, -1};
    stars_.rename_corner(t, v, u);
    energy_[t] = kStale;
    for (int x : stars_.corners(t)) touched_[x] = clock_;
  }
}

std::vector<std::array<int, 2>> Optimizer::boundary_link(int x) const {
  std::vector<std::array<int, 3>> faces;
  for (int t : stars_.star(x)) {
    const Tet& q = stars_.corners(t);
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

bool Optimizer::boundary_link_condition(int u, int v) const {
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

bool Optimizer::too_long(int a, int b) const {
  return max_edge_length_ > 0 && (m_.v.d[a] - m_.v.d[b]).norm() > max_edge_length_;
}

} // namespace curvetet::volume::exact

#include "curvetet/volume/exact_optimizer.hpp"

#include "curvetet/core/error.hpp"

#include <algorithm>
#include <vector>

namespace curvetet::volume::exact {

Optimizer::Optimizer(ExactTetMesh&& m, FillStats& stats, const FillOptions& options)
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

int Optimizer::add_vertex(const Vec3& p) {
  const int v = m_.v.add(p);
  m_.frozen.push_back(0);
  vt_.emplace_back();
  pinned_.push_back(0);
  touched_.push_back(++clock_);
  smooth_failed_.push_back(0);
  max_failed_.push_back(0);
  return v;
}

void Optimizer::move(int v, const Vec3& p) {
  m_.v.set(v, p);
  touched_[v] = ++clock_;
  for (int t : vt_[v]) energy_[t] = kStale;
}

std::size_t Optimizer::round_pass() {
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

std::size_t Optimizer::count_rational() const {
  std::size_t n = 0;
  for (int v = 0; v < m_.v.size(); ++v) n += !m_.v.exact[v] && !vt_[v].empty();
  return n;
}

bool Optimizer::unchanged_since(int v, std::uint64_t when) const {
  if (when == 0 || touched_[v] > when) return false;
  for (int t : vt_[v])
    for (int x : m_.tets[t])
      if (touched_[x] > when) return false;
  return true;
}

bool Optimizer::flips_known_to_fail(int t) const {
  const std::uint64_t when = flip_failed_[t];
  return when != 0 && std::all_of(m_.tets[t].begin(), m_.tets[t].end(), [&](int x) { return unchanged_since(x, when); });
}

int Optimizer::across(int t, int k) const {
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

void Optimizer::begin_journal() {
  journal_.clear();
  saved_touched_.clear();
  journaling_ = true;
}

void Optimizer::undo_journal() {
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

std::vector<int> Optimizer::neighbours(int v) const {
  std::vector<int> out;
  for (int t : vt_[v])
    for (int x : m_.tets[t])
      if (x != v) out.push_back(x);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

mesh::LinearTetMesh Optimizer::extract(int num_keep) {
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

void Optimizer::kill(int t) {
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

int Optimizer::add(const Tet& t) {
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

bool Optimizer::edge_exists(int a, int b) const {
  for (int t : vt_[a]) {
    const Tet& q = m_.tets[t];
    if (std::find(q.begin(), q.end(), b) != q.end()) return true;
  }
  return false;
}

bool Optimizer::face_exists(int a, int b, int c) const {
  for (int t : vt_[a]) {
    const Tet& q = m_.tets[t];
    if (std::find(q.begin(), q.end(), b) != q.end() && std::find(q.begin(), q.end(), c) != q.end()) return true;
  }
  return false;
}

} // namespace curvetet::volume::exact

#include "curvetet/volume/exact_optimizer.hpp"

#include "curvetet/core/error.hpp"

#include <algorithm>
#include <vector>

namespace curvetet::volume::exact {

Optimizer::Optimizer(ExactTetMesh&& m, FillStats& stats, const FillOptions& options)
    : m_(std::move(m)), stats_(stats), coarsen_energy_(options.coarsen_energy),
      max_edge_length_(options.max_edge_length) {
  stars_ = edit::TetStars(std::move(m_.tets), m_.v.size());
  m_.tets.clear(); // the tets live in stars_ from now on
  across_.assign(stars_.num_slots(), {-1, -1, -1, -1});
  energy_.assign(stars_.num_slots(), kStale);
  flip_failed_.assign(stars_.num_slots(), 0);
  touched_.assign(m_.v.size(), 0);
  smooth_failed_.assign(m_.v.size(), 0);
  max_failed_.assign(m_.v.size(), 0);
  pinned_.assign(m_.v.size(), 0);
  for (const auto& st : m_.on_surface) pinned_[st.vertex] = 1;
}

int Optimizer::add_vertex(const Vec3& p) {
  const int v = m_.v.add(p);
  m_.frozen.push_back(0);
  stars_.add_vertex();
  pinned_.push_back(0);
  touched_.push_back(++clock_);
  smooth_failed_.push_back(0);
  max_failed_.push_back(0);
  return v;
}

void Optimizer::move(int v, const Vec3& p) {
  m_.v.set(v, p);
  touched_[v] = ++clock_;
  for (int t : stars_.star(v)) energy_[t] = kStale;
}

std::size_t Optimizer::round_pass() {
  std::size_t left = 0;
  for (int v = 0; v < m_.v.size(); ++v) {
    if (m_.v.exact[v] || stars_.star(v).empty() || pinned(v)) continue;
    const Vec3 p = nearest_double(m_.v.q[v]);
    if (star_positive_at(v, p)) {
      move(v, p);
    } else {
      ++left;
    }
  }
  return left;
}

std::size_t Optimizer::num_alive() const {
  std::size_t n = 0;
  for (int t = 0; t < num_tets(); ++t) n += stars_.alive(t);
  return n;
}

std::size_t Optimizer::count_rational() const {
  std::size_t n = 0;
  for (int v = 0; v < m_.v.size(); ++v) n += !m_.v.exact[v] && !stars_.star(v).empty();
  return n;
}

bool Optimizer::unchanged_since(int v, std::uint64_t when) const {
  if (when == 0 || touched_[v] > when) return false;
  for (int t : stars_.star(v))
    for (int x : stars_.corners(t))
      if (touched_[x] > when) return false;
  return true;
}

bool Optimizer::flips_known_to_fail(int t) const {
  const std::uint64_t when = flip_failed_[t];
  return when != 0 && std::all_of(stars_.corners(t).begin(), stars_.corners(t).end(), [&](int x) { return unchanged_since(x, when); });
}

int Optimizer::across(int t, int k) const {
  if (const int n = across_[t][k]; n >= 0 && stars_.alive(n)) return n;
  const Tet& q = stars_.corners(t);
  int a = q[(k + 1) % 4], b = q[(k + 2) % 4], c = q[(k + 3) % 4];
  if (stars_.star(b).size() < stars_.star(a).size()) std::swap(a, b); // scan the smallest star
  if (stars_.star(c).size() < stars_.star(a).size()) std::swap(a, c);
  for (int s : stars_.star(a)) {
    if (s == t) continue;
    const Tet& r = stars_.corners(s);
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
    if (was_added && stars_.alive(t)) kill(t);
  for (const auto& [t, was_added] : journal)
    if (!was_added && !std::binary_search(added.begin(), added.end(), t)) {
      const Tet copy = stars_.corners(t); // add() may reallocate the slots
      const std::uint64_t stamp = flip_failed_[t];
      flip_failed_[add(copy)] = stamp;
    }
  for (auto it = saved_touched_.rbegin(); it != saved_touched_.rend(); ++it) touched_[it->first] = it->second;
  saved_touched_.clear();
}

mesh::LinearTetMesh Optimizer::extract(int num_keep) {
  mesh::LinearTetMesh out;
  std::vector<int> id(m_.v.size(), -1);
  for (int v = 0; v < num_keep; ++v) id[v] = v;
  int next = num_keep;
  for (int t = 0; t < num_tets(); ++t)
    if (stars_.alive(t))
      for (int x : stars_.corners(t))
        if (id[x] < 0) id[x] = next++;
  out.vertices.resize(next);
  for (int v = 0; v < m_.v.size(); ++v)
    if (id[v] >= 0) {
      if (!m_.v.exact[v]) throw Error(ExitCode::internal, "volume: a vertex could not be rounded to doubles");
      out.vertices[id[v]] = m_.v.d[v];
    }
  for (int t = 0; t < num_tets(); ++t)
    if (stars_.alive(t)) {
      const Tet& q = stars_.corners(t);
      out.tets.push_back({id[q[0]], id[q[1]], id[q[2]], id[q[3]]});
    }
  return out;
}

void Optimizer::kill(int t) {
  if (!stars_.alive(t)) throw Error(ExitCode::internal, "volume: optimizer removed a tet twice");
  if (journaling_) journal_.emplace_back(t, false);
  stars_.kill(t);
  ++clock_;
  for (int x : stars_.corners(t)) {
    if (journaling_) saved_touched_.emplace_back(x, touched_[x]);
    touched_[x] = clock_;
  }
}

int Optimizer::add(const Tet& t) { // t may be one of ours: stars_.add copies it first
  const int id = stars_.add(t);
  across_.push_back({-1, -1, -1, -1});
  energy_.push_back(kStale);
  flip_failed_.push_back(0);
  ++clock_;
  for (int x : stars_.corners(id)) {
    if (journaling_) saved_touched_.emplace_back(x, touched_[x]);
    touched_[x] = clock_;
  }
  if (journaling_) journal_.emplace_back(id, true);
  return id;
}

} // namespace curvetet::volume::exact

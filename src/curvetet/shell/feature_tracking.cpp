#include "curvetet/shell/feature_tracking.hpp"

#include "curvetet/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <unordered_map>

namespace curvetet::shell {

// ---- ShellFeatures queries ----------------------------------------------

bool ShellFeatures::closed(int k) const { return chains[k].closed || chains[k].vertices.front() == chains[k].vertices.back(); }

double ShellFeatures::wrap(int k, double p) const {
  if (!chains[k].closed) return p;
  const double n = num_positions(k);
  p = std::fmod(p, n);
  return p < 0 ? p + n : p;
}

int ShellFeatures::input_vertex(int k, long long p) const {
  const auto& c = chains[k];
  if (!c.closed) return c.vertices[p];
  const long long n = c.num_edges();
  return c.vertices[((p % n) + n) % n];
}

double ShellFeatures::arc_at(int k, double p) const {
  const auto& a = arc[k];
  const int n = num_positions(k);
  double turns = 0;
  if (chains[k].closed) {
    turns = std::floor(p / n);
    p -= turns * n;
  }
  const int i = std::clamp(static_cast<int>(std::floor(p)), 0, n - 1 < 0 ? 0 : n - 1);
  const double frac = p - i;
  return turns * a[n] + a[i] + frac * (a[i + 1] - a[i]);
}

namespace {

std::vector<std::vector<int>> shell_neighbours(const Shell& s) {
  std::vector<std::vector<int>> nb(s.num_vertices());
  for (const auto& t : s.faces)
    for (int k = 0; k < 3; ++k) {
      nb[t[k]].push_back(t[(k + 1) % 3]);
      nb[t[(k + 1) % 3]].push_back(t[k]);
    }
  for (auto& l : nb) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
  return nb;
}

bool adjacent(const std::vector<std::vector<int>>& nb, int a, int b) {
  return std::binary_search(nb[a].begin(), nb[a].end(), b);
}

// Integer positions strictly inside (lo, hi).
long long first_inside(double lo) { return static_cast<long long>(std::floor(lo)) + 1; }
long long last_inside(double hi) { return static_cast<long long>(std::ceil(hi)) - 1; }

// The integer position in (lo, hi) whose input vertex is bitwise at x.
std::optional<long long> position_of_point(const ShellFeatures& f, const mesh::SurfaceMesh& input, int k, double lo,
                                           double hi, const Vec3& x) {
  for (long long p = first_inside(lo); p <= last_inside(hi); ++p)
    if (input.vertices[f.input_vertex(k, p)] == x) return p;
  return std::nullopt;
}

int moved_index(const StarCandidate& c, int v) {
  for (std::size_t i = 0; i < c.moved.size(); ++i)
    if (c.moved[i] == v) return static_cast<int>(i);
  return -1;
}

} // namespace

// ---- attach ---------------------------------------------------------------

void attach_features(Shell& s, const features::FeatureGraph& g) {
  ShellFeatures f;
  f.chains = g.chains;
  f.input_corners = g.corners;
  f.input_faces_around = mesh::build_vertex_faces(s.input.num_vertices(), s.input.faces);
  for (const auto& c : f.chains) {
    std::vector<double> a{0.0};
    const int n = c.num_edges();
    for (int i = 0; i < n; ++i) {
      const int u = c.vertices[i], w = c.vertices[(i + 1) % c.vertices.size()];
      a.push_back(a.back() + (s.input.vertices[w] - s.input.vertices[u]).norm());
    }
    f.arc.push_back(std::move(a));
  }
  const int nv = s.num_vertices();
  f.corner_input.assign(nv, -1);
  f.chain.assign(nv, -1);
  f.position.assign(nv, 0);
  f.prev.assign(nv, -1);
  f.next.assign(nv, -1);
  f.chain_edges.assign(f.chains.size(), 0);
  for (int c : g.corners) f.corner_input[c] = c;

  const auto nb = shell_neighbours(s);
  // Follows input edge (u, w) at positions [pu, pw] through isolation
  // midpoints; appends the shell vertices strictly between, in order.
  std::function<void(int, double, int, double, std::vector<std::pair<int, double>>&)> resolve =
      [&](int u, double pu, int w, double pw, std::vector<std::pair<int, double>>& out) {
        if (adjacent(nb, u, w)) return;
        const Vec3 mid = 0.5 * (s.middle[u] + s.middle[w]);
        for (int m : nb[u])
          if (m >= s.input.num_vertices() && adjacent(nb, m, w) && s.middle[m] == mid) {
            const double pm = 0.5 * (pu + pw);
            resolve(u, pu, m, pm, out);
            out.push_back({m, pm});
            resolve(m, pm, w, pw, out);
            return;
          }
        throw Error(ExitCode::internal, fmt::format("features: input feature edge ({}, {}) is not in the shell", u, w));
      };

  for (int k = 0; k < static_cast<int>(f.chains.size()); ++k) {
    const auto& c = f.chains[k];
    const int n = c.num_edges();
    // Shell vertices along the chain with their positions.
    std::vector<std::pair<int, double>> seq{{c.vertices[0], 0.0}};
    for (int i = 0; i < n; ++i) {
      const int u = c.vertices[i], w = c.vertices[(i + 1) % c.vertices.size()];
      resolve(u, i, w, i + 1, seq);
      seq.push_back({w, i + 1.0});
    }
    for (std::size_t i = 0; i + 1 < seq.size(); ++i) {
      const auto [u, pu] = seq[i];
      const auto [w, pw] = seq[i + 1];
      f.edges[ShellFeatures::edge_key(u, w)] = CoarseFeatureEdge{k, u, f.wrap(k, pu), pw - pu};
      ++f.chain_edges[k];
    }
    // Interior vertices: all but the ends of an open chain (corners).
    const std::size_t m = seq.size() - 1; // seq.back() repeats seq.front() for loops
    for (std::size_t i = 0; i < m; ++i) {
      const int v = seq[i].first;
      if (f.corner_input[v] >= 0) continue;
      f.chain[v] = k;
      f.position[v] = f.wrap(k, seq[i].second);
      f.prev[v] = i > 0 ? seq[i - 1].first : seq[m - 1].first;
      f.next[v] = seq[i + 1].first;
    }
  }
  s.features = std::move(f);
}

// ---- planning -------------------------------------------------------------

const CoarseFeatureEdge* FeatureEdit::edge_after(const ShellFeatures& f, int a, int b) const {
  const auto key = ShellFeatures::edge_key(a, b);
  for (const auto& [e, rec] : added)
    if (ShellFeatures::edge_key(e[0], e[1]) == key) return &rec;
  if (std::find(erased.begin(), erased.end(), key) != erased.end()) return nullptr;
  return f.edge(a, b);
}

FeatureEdit plan_feature_edit(const Shell& s, const StarCandidate& c) {
  FeatureEdit out;
  const ShellFeatures& f = s.features;
  if (f.empty()) return out;
  auto reject = [&] {
    out.allowed = false;
    return out;
  };
  auto is_feature_vertex = [&](int v) { return v != kNewVertex && (f.is_corner(v) || f.chain_of(v) >= 0); };
  auto vertex_record = [&](int v) {
    return FeatureEdit::Vertex{v, f.chain[v], f.position[v], f.prev[v], f.next[v]};
  };
  // Updates v's record in the plan (creating it from the current one).
  auto vertex_in_plan = [&](int v) -> FeatureEdit::Vertex& {
    for (auto& r : out.vertices)
      if (r.v == v) return r;
    out.vertices.push_back(vertex_record(v));
    return out.vertices.back();
  };

  // Any operation but smoothing and a feature split keeps feature vertices
  // where they are.
  if (c.op != OpKind::smooth)
    for (std::size_t i = 0; i < c.moved.size(); ++i) {
      const int v = c.moved[i];
      if (is_feature_vertex(v) && c.moved_middle[i] != s.middle[v]) return reject();
    }

  switch (c.op) {
    case OpKind::flip:
      if (f.edge(c.edge[0], c.edge[1])) return reject();
      return out;

    case OpKind::collapse: {
      const int from = c.edge[0], to = c.edge[1];
      if (f.is_corner(from)) return reject();
      const int k = f.chain_of(from);
      if (k < 0) return out; // no feature edge at `from`: nothing changes
      const CoarseFeatureEdge* e = f.edge(from, to);
      if (!e || e->chain != k) return reject();
      if (f.chain_edges[k] - 1 < (f.closed(k) ? 3 : 1)) return reject();
      const int P = f.prev[from], N = f.next[from];
      const CoarseFeatureEdge* e1 = f.edge(P, from);
      const CoarseFeatureEdge* e2 = f.edge(from, N);
      out.erased = {ShellFeatures::edge_key(P, from), ShellFeatures::edge_key(from, N)};
      out.added.push_back({{P, N}, CoarseFeatureEdge{k, P, e1->start, e1->length + e2->length}});
      out.vertices.push_back({from, -1, 0, -1, -1});
      if (f.chain_of(P) == k) vertex_in_plan(P).next = N;
      if (f.chain_of(N) == k) vertex_in_plan(N).prev = P;
      return out;
    }

    case OpKind::split: {
      const CoarseFeatureEdge* e = f.edge(c.edge[0], c.edge[1]);
      if (!e) return out;
      const int k = e->chain;
      const int first = e->first, other = first == c.edge[0] ? c.edge[1] : c.edge[0];
      const int i = moved_index(c, kNewVertex);
      if (i < 0) return reject();
      const auto p = position_of_point(f, s.input, k, e->start, e->start + e->length, c.moved_middle[i]);
      if (!p) return reject();
      const double pm = static_cast<double>(*p);
      out.erased = {ShellFeatures::edge_key(first, other)};
      out.added.push_back({{first, kNewVertex}, CoarseFeatureEdge{k, first, e->start, pm - e->start}});
      out.added.push_back({{kNewVertex, other}, CoarseFeatureEdge{k, kNewVertex, f.wrap(k, pm), e->start + e->length - pm}});
      out.vertices.push_back({kNewVertex, k, f.wrap(k, pm), first, other});
      if (f.chain_of(first) == k) vertex_in_plan(first).next = kNewVertex;
      if (f.chain_of(other) == k) vertex_in_plan(other).prev = kNewVertex;
      return out;
    }

    case OpKind::smooth: {
      for (std::size_t i = 0; i < c.moved.size(); ++i) {
        const int v = c.moved[i];
        if (c.moved_middle[i] == s.middle[v] || !is_feature_vertex(v)) continue;
        if (f.is_corner(v)) return reject();
        const int k = f.chain[v];
        const CoarseFeatureEdge* e1 = f.edge(f.prev[v], v);
        const CoarseFeatureEdge* e2 = f.edge(v, f.next[v]);
        const double lo = e1->start, total = e1->length + e2->length;
        const auto q = position_of_point(f, s.input, k, lo, lo + total, c.moved_middle[i]);
        if (!q) return reject();
        const double pq = static_cast<double>(*q);
        out.added.push_back({{f.prev[v], v}, CoarseFeatureEdge{k, f.prev[v], lo, pq - lo}});
        out.added.push_back({{v, f.next[v]}, CoarseFeatureEdge{k, v, f.wrap(k, pq), lo + total - pq}});
        vertex_in_plan(v).position = f.wrap(k, pq);
      }
      return out;
    }
  }
  return out;
}

// ---- applying ---------------------------------------------------------------

void apply_feature_edit(Shell& s, const StarCandidate& c, int new_vertex) {
  ShellFeatures& f = s.features;
  if (f.empty()) return;
  const FeatureEdit plan = plan_feature_edit(s, c);
  if (!plan.allowed) throw Error(ExitCode::internal, "features: committing an operation the feature rules reject");
  auto id = [&](int v) { return v == kNewVertex ? new_vertex : v; };
  const int nv = std::max(s.num_vertices(), new_vertex + 1);
  if (static_cast<int>(f.chain.size()) < nv) {
    f.corner_input.resize(nv, -1);
    f.chain.resize(nv, -1);
    f.position.resize(nv, 0);
    f.prev.resize(nv, -1);
    f.next.resize(nv, -1);
  }
  for (auto key : plan.erased) f.edges.erase(key);
  int delta = -static_cast<int>(plan.erased.size());
  for (const auto& [e, rec] : plan.added) {
    CoarseFeatureEdge r = rec;
    r.first = id(r.first);
    const auto key = ShellFeatures::edge_key(id(e[0]), id(e[1]));
    delta += f.edges.count(key) == 0;
    f.edges[key] = r;
  }
  // Edge count per chain: every plan touches one chain.
  if (!plan.added.empty()) f.chain_edges[plan.added.front().second.chain] += delta;
  for (const auto& r : plan.vertices) {
    const int v = id(r.v);
    f.chain[v] = r.chain;
    f.position[v] = r.position;
    f.prev[v] = r.prev < 0 ? -1 : id(r.prev);
    f.next[v] = r.next < 0 ? -1 : id(r.next);
  }
}

void remap_feature_vertices(ShellFeatures& f, const std::vector<int>& vmap, int count) {
  if (f.empty()) return;
  auto keep = [&](auto& vec) {
    std::decay_t<decltype(vec)> out(count);
    for (std::size_t v = 0; v < vmap.size() && v < vec.size(); ++v)
      if (vmap[v] >= 0) out[vmap[v]] = vec[v];
    vec = std::move(out);
  };
  keep(f.corner_input);
  keep(f.chain);
  keep(f.position);
  keep(f.prev);
  keep(f.next);
  auto map_id = [&](int v) { return v < 0 ? -1 : vmap[v]; };
  for (auto& v : f.prev) v = map_id(v);
  for (auto& v : f.next) v = map_id(v);
  std::unordered_map<std::uint64_t, CoarseFeatureEdge> edges;
  edges.reserve(f.edges.size());
  for (const auto& [key, rec] : f.edges) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    CoarseFeatureEdge r = rec;
    r.first = vmap[r.first];
    edges[ShellFeatures::edge_key(vmap[a], vmap[b])] = r;
  }
  f.edges = std::move(edges);
  for (auto& e : f.on_edge)
    if (e.a >= 0) e = {vmap[e.a], vmap[e.b], e.t};
}

// ---- proposals ----------------------------------------------------------------

std::optional<Vec3> feature_split_point(const Shell& s, int a, int b) {
  const ShellFeatures& f = s.features;
  const CoarseFeatureEdge* e = f.empty() ? nullptr : f.edge(a, b);
  if (!e) return std::nullopt;
  const double lo = e->start, hi = e->start + e->length;
  const double target = 0.5 * (f.arc_at(e->chain, lo) + f.arc_at(e->chain, hi));
  std::optional<long long> best;
  double best_d = 0;
  for (long long p = first_inside(lo); p <= last_inside(hi); ++p) {
    const double d = std::abs(f.arc_at(e->chain, static_cast<double>(p)) - target);
    if (!best || d < best_d) {
      best = p;
      best_d = d;
    }
  }
  if (!best) return std::nullopt;
  return s.input.vertices[f.input_vertex(e->chain, *best)];
}

std::optional<std::vector<Vec3>> feature_pan_targets(const Shell& s, int v) {
  const ShellFeatures& f = s.features;
  if (f.empty()) return std::nullopt;
  if (f.is_corner(v)) return std::vector<Vec3>{};
  const int k = f.chain_of(v);
  if (k < 0) return std::nullopt;
  const CoarseFeatureEdge* e1 = f.edge(f.prev[v], v);
  const CoarseFeatureEdge* e2 = f.edge(v, f.next[v]);
  std::vector<Vec3> out;
  const double lo = e1->start, hi = e1->start + e1->length + e2->length;
  for (long long p = first_inside(lo); p <= last_inside(hi); ++p) out.push_back(s.input.vertices[f.input_vertex(k, p)]);
  return out;
}

// ---- distance and verification ------------------------------------------------

double feature_edge_distance(const ShellFeatures& f, const mesh::SurfaceMesh& input, const CoarseFeatureEdge& e,
                             const std::function<Vec3(double t)>& curve) {
  const int k = e.chain;
  const double lo = e.start, hi = e.start + e.length;
  const double a0 = f.arc_at(k, lo), a1 = f.arc_at(k, hi);
  const double span = a1 - a0;
  double worst = 0;
  for (long long p = static_cast<long long>(std::ceil(lo)); p <= static_cast<long long>(std::floor(hi)); ++p) {
    const double t = span > 0 ? (f.arc_at(k, static_cast<double>(p)) - a0) / span : 0.0;
    worst = std::max(worst, (input.vertices[f.input_vertex(k, p)] - curve(t)).norm());
  }
  return worst;
}

FeatureCheck check_features(const Shell& s) {
  FeatureCheck out;
  const ShellFeatures& f = s.features;
  if (f.empty()) return out;
  auto problem = [&](const std::string& what) {
    if (out.first_problem.empty()) out.first_problem = what;
  };
  // Corners: a live shell vertex each, at the input position.
  std::vector<int> shell_of_corner(s.input.num_vertices(), -1);
  for (int v = 0; v < static_cast<int>(f.corner_input.size()) && v < s.num_vertices(); ++v)
    if (f.corner_input[v] >= 0) shell_of_corner[f.corner_input[v]] = v;
  out.corners = static_cast<int>(f.input_corners.size());
  for (int c : f.input_corners) {
    const int v = shell_of_corner[c];
    if (v < 0) {
      ++out.corners_missing;
      problem(fmt::format("input corner {} is not a shell vertex", c));
    } else if (s.middle[v] != s.input.vertices[c]) {
      ++out.corners_moved;
      problem(fmt::format("corner {} (shell vertex {}) moved", c, v));
    }
  }
  // Chains: the coarse edges, sorted by start, cover each chain end to end.
  std::set<std::uint64_t> shell_edges;
  // One prism per edge: where the curved middle edge is evaluated.
  std::unordered_map<std::uint64_t, int> prism_of_edge;
  for (int p = 0; p < s.num_prisms(); ++p) {
    const auto& t = s.faces[p];
    for (int k = 0; k < 3; ++k) {
      const auto key = ShellFeatures::edge_key(t[k], t[(k + 1) % 3]);
      shell_edges.insert(key);
      prism_of_edge.emplace(key, p);
    }
  }
  const bool curved = !s.middle_nodes.empty();
  const int K = static_cast<int>(f.chains.size());
  out.chains = K;
  std::vector<std::vector<std::pair<int, int>>> per_chain(K); // (first, other)
  std::vector<std::vector<const CoarseFeatureEdge*>> recs(K);
  for (const auto& [key, e] : f.edges) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    recs[e.chain].push_back(&e);
    per_chain[e.chain].push_back({e.first, e.first == a ? b : a});
    ++out.coarse_edges;
    if (!shell_edges.count(key)) {
      ++out.missing_edges;
      problem(fmt::format("coarse feature edge ({}, {}) is not a shell edge", a, b));
    }
    const int other = e.first == a ? b : a;
    const Vec3 pa = s.middle[e.first], pb = s.middle[other];
    std::function<Vec3(double)> curve = [&](double t) { return ((1 - t) * pa + t * pb).eval(); };
    const auto pe = prism_of_edge.find(key);
    if (curved && pe != prism_of_edge.end()) {
      // The middle edge as the output has it: the prism's curved triangle
      // restricted to that edge (edge nodes agree between its two prisms).
      const auto& t = s.faces[pe->second];
      const int i = static_cast<int>(std::find(t.begin(), t.end(), e.first) - t.begin());
      const int j = static_cast<int>(std::find(t.begin(), t.end(), other) - t.begin());
      curve = [&s, p = pe->second, i, j](double t) {
        std::array<double, 3> w{0, 0, 0};
        w[i] = 1 - t;
        w[j] = t;
        return middle_point(s, MapPoint{p, w[1], w[2]});
      };
    }
    out.max_distance = std::max(out.max_distance, feature_edge_distance(f, s.input, e, curve));
  }
  for (int k = 0; k < K; ++k) {
    auto& r = recs[k];
    std::vector<int> order(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) order[i] = static_cast<int>(i);
    std::sort(order.begin(), order.end(), [&](int x, int y) { return r[x]->start < r[y]->start; });
    const int n = f.num_positions(k);
    bool ok = !r.empty() && static_cast<int>(r.size()) == f.chain_edges[k];
    double total = 0;
    for (std::size_t i = 0; ok && i < order.size(); ++i) {
      const auto* e = r[order[i]];
      const auto& ends = per_chain[k][order[i]];
      total += e->length;
      if (!(e->length > 0)) ok = false;
      if (!shell_edges.count(ShellFeatures::edge_key(ends.first, ends.second))) ok = false;
      if (i + 1 < order.size()) {
        const auto* nx = r[order[i + 1]];
        if (nx->start != e->start + e->length || per_chain[k][order[i + 1]].first != ends.second) ok = false;
      } else if (f.chains[k].closed) {
        if (per_chain[k][order[0]].first != ends.second) ok = false;
      }
    }
    if (ok && total != n) ok = false;
    if (ok && !f.chains[k].closed) {
      const auto& front = per_chain[k][order.front()];
      const auto& back = per_chain[k][order.back()];
      if (r[order.front()]->start != 0 || front.first != shell_of_corner[f.chains[k].vertices.front()] ||
          back.second != shell_of_corner[f.chains[k].vertices.back()])
        ok = false;
    }
    if (!ok) {
      ++out.broken_chains;
      problem(fmt::format("chain {} is not covered end to end by its coarse edges", k));
    }
  }
  return out;
}

} // namespace curvetet::shell

#include "curvetet/shell/layer_growth.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/mesh/edge_topology.hpp"
#include "curvetet/shell/invariant_set.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <memory>

namespace curvetet::shell {

namespace {

constexpr int kMaxHalvings = 80;

struct Grower {
  Shell& s;
  const LayerGrowthSpec& spec;
  std::vector<double>& len;
  mesh::VertexFaces vf;
  std::vector<std::vector<int>> trackers;
  std::unique_ptr<CapIndex> caps; // built once the initial layer is placed
  std::vector<std::vector<int>> neighbours;
  InvariantSet invariants = InvariantSet::shell_invariants();

  void place(int v) {
    const Vec3& d = spec.direction[v];
    if (d.isZero() || len[v] == 0) {
      s.top[v] = s.middle[v];
      s.bottom[v] = s.middle[v];
      return;
    }
    s.top[v] = spec.grow_top ? Vec3(s.middle[v] + len[v] * d) : s.middle[v];
    s.bottom[v] = spec.grow_bottom ? Vec3(s.middle[v] - len[v] * d) : s.middle[v];
  }

  std::vector<int> prisms_of(const std::vector<int>& vertices) const {
    std::vector<int> out;
    for (int v : vertices)
      for (int i = vf.offsets[v]; i < vf.offsets[v + 1]; ++i) out.push_back(vf.faces[i]);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  // Prisms among (or meeting caps of) `prisms` that break invariant 1-3.
  std::vector<int> implicated(const std::vector<int>& prisms) {
    caps->update(s, prisms);
    return invariants.implicated(s, prisms, InvariantContext{&trackers, caps.get()});
  }

  void stop_if_requested() const {
    if (spec.stop_requested && spec.stop_requested()) throw Stopped{};
  }

  std::vector<int> vertices_of(const std::vector<int>& prisms) const {
    std::vector<int> out;
    for (int f : prisms)
      for (int v : s.faces[f]) out.push_back(v);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
};

} // namespace

Shell flat_shell(const mesh::SurfaceMesh& surface) {
  Shell s;
  s.middle = surface.vertices;
  s.top = s.bottom = s.middle;
  s.faces = surface.faces;
  s.input = surface;
  s.tracked.resize(surface.num_faces());
  for (int f = 0; f < surface.num_faces(); ++f) s.tracked[f] = {f};
  s.singular.assign(surface.num_vertices(), 0);
  return s;
}

LayerGrowthStats grow_layer(Shell& s, const LayerGrowthSpec& spec, std::vector<double>& len) {
  using clock = std::chrono::steady_clock;
  LayerGrowthStats stats;
  const int n = s.num_vertices();
  s.top = s.middle;
  s.bottom = s.middle;
  len.assign(n, 0.0);
  Grower g{s, spec, len, mesh::build_vertex_faces(n, s.faces), input_trackers(s)};
  g.neighbours.resize(n);
  for (const auto& f : s.faces)
    for (int k = 0; k < 3; ++k) g.neighbours[f[k]].push_back(f[(k + 1) % 3]);

  // 1. Initial thin layer.
  auto t0 = clock::now();
  std::vector<int> changed;
  for (int v = 0; v < n; ++v)
    if (!spec.direction[v].isZero()) {
      len[v] = spec.initial;
      g.place(v);
      changed.push_back(v);
    }
  g.caps = std::make_unique<CapIndex>(s);
  if (spec.stop_requested) g.caps->poll = [&g] { g.stop_if_requested(); };
  while (!changed.empty()) {
    g.stop_if_requested();
    const auto bad = g.implicated(g.prisms_of(changed));
    if (bad.empty()) break;
    if (++stats.initial_halvings > kMaxHalvings)
      throw Error(ExitCode::internal, fmt::format("shell: no valid initial layer after {} halvings ({} prisms fail, "
                                                  "first {})",
                                                  kMaxHalvings, bad.size(), bad.front()));
    changed.clear();
    for (int v : g.vertices_of(bad))
      if (len[v] > 0) {
        len[v] *= 0.5;
        g.place(v);
        changed.push_back(v);
      }
    if (changed.empty())
      throw Error(ExitCode::internal, fmt::format("shell: prism {} fails with all its pillars pinched", bad.front()));
  }
  stats.seconds_initial = std::chrono::duration<double>(clock::now() - t0).count();
  if (spec.after_stage) spec.after_stage(s, "initial layer");

  // 2. Thickening rounds.
  t0 = clock::now();
  std::vector<double> factor(n, spec.growth_factor);
  std::vector<char> done(n, 0);
  for (int v = 0; v < n; ++v) done[v] = spec.direction[v].isZero() || len[v] >= spec.target;
  for (int round = 0; round < spec.max_rounds; ++round) {
    // Proposals, limited to neighbour_ratio x the thinnest non-singular
    // neighbour so that no vertex outgrows a stuck neighbour (mixed-length
    // prisms are what blocks growth).
    const std::vector<double> old = len;
    std::vector<double> proposal(n, 0.0);
    changed.clear();
    for (int v = 0; v < n; ++v) {
      if (done[v]) continue;
      double cap = spec.target;
      for (int w : g.neighbours[v])
        if (!spec.direction[w].isZero()) cap = std::min(cap, spec.neighbour_ratio * old[w]);
      proposal[v] = std::min(cap, old[v] * factor[v]);
      if (proposal[v] > old[v]) changed.push_back(v);
    }
    if (changed.empty()) break;
    ++stats.rounds;
    for (int v : changed) {
      len[v] = proposal[v];
      g.place(v);
    }
    std::vector<char> failed(n, 0);
    std::vector<int> check = g.prisms_of(changed);
    int iterations = 0;
    while (!check.empty()) {
      ++iterations;
      g.stop_if_requested();
      const auto bad = g.implicated(check);
      if (bad.empty()) break;
      std::vector<int> reverted;
      for (int v : g.vertices_of(bad))
        if (len[v] != old[v]) {
          len[v] = old[v];
          g.place(v);
          failed[v] = 1;
          reverted.push_back(v);
        }
      if (reverted.empty())
        throw Error(ExitCode::internal,
                    fmt::format("shell: prism {} invalid although none of its vertices moved", bad.front()));
      stats.reverts += static_cast<long long>(reverted.size());
      check = g.prisms_of(reverted);
    }
    int grown = 0;
    for (int v : changed) {
      if (failed[v]) {
        factor[v] = std::sqrt(factor[v]);
        if (factor[v] < spec.min_factor) done[v] = 1;
      } else {
        ++grown;
        if (len[v] >= spec.target) done[v] = 1;
      }
    }
    logger().debug("shell: thickening round {}: {} of {} vertices grew ({} check passes)", round + 1, grown,
                   changed.size(), iterations);
  }
  stats.seconds_rounds = std::chrono::duration<double>(clock::now() - t0).count();
  if (spec.after_stage) spec.after_stage(s, "thickening");
  return stats;
}

} // namespace curvetet::shell

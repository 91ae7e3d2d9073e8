#include "curvetet/volume/curved_remesh.hpp"

#include "curvetet/core/log.hpp"
#include "curvetet/highorder/quality.hpp"
#include "curvetet/volume/edit/operations.hpp"
#include "curvetet/volume/edit/tet_editor.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>

namespace curvetet::volume {
namespace {

using edit::Proposal;
using edit::Reject;
using edit::StarLimits;
using edit::TetEditor;

struct Summary {
  double max_amips = 0, mean_amips = 0, min_scaled_jacobian = 0;
};

Summary summarize(const mesh::TetMesh& m) {
  const int n = m.num_tets();
  std::vector<highorder::TetQuality> q(n);
  tbb::parallel_for(0, n, [&](int t) {
    std::vector<Eigen::Vector3d> nodes(m.tet_nodes());
    m.tet_positions(t, nodes.data());
    q[t] = highorder::tet_quality(m.order, nodes.data());
  });
  Summary s;
  s.min_scaled_jacobian = n ? std::numeric_limits<double>::infinity() : 0;
  for (const auto& x : q) {
    s.max_amips = std::max(s.max_amips, x.max_amips);
    s.mean_amips += x.mean_amips / n;
    s.min_scaled_jacobian = std::min(s.min_scaled_jacobian, x.min_scaled_jacobian);
  }
  return s;
}

// Worst shape of the tets a proposal kills.
edit::TetShape old_star(const TetEditor& e, const Proposal& p) {
  edit::TetShape s{0, std::numeric_limits<double>::infinity()};
  for (int t : p.kill) {
    s.max_amips = std::max(s.max_amips, e.shape(t).max_amips);
    s.min_scaled_jacobian = std::min(s.min_scaled_jacobian, e.shape(t).min_scaled_jacobian);
  }
  return s;
}

class Remesher {
 public:
  Remesher(TetEditor& e, const CurvedRemeshOptions& o, CurvedRemeshStats& s) : e_(e), o_(o), s_(s) {}

  // Runs p as a transaction; keeps it when every new tet passes the checks.
  bool apply(const Proposal& p, const StarLimits& limits) {
    e_.begin();
    for (int t : p.kill) e_.kill(t);
    for (const auto& [c, tag] : p.add) e_.add(c, tag);
    if (const auto why = edit::check_new_tets(e_, limits)) {
      e_.rollback();
      ++s_.rejected[static_cast<int>(*why)];
      return false;
    }
    e_.commit();
    return true;
  }

  // Max AMIPS and min scaled Jacobian the new tets of p would have.
  edit::TetShape preview(const Proposal& p) {
    e_.begin();
    for (int t : p.kill) e_.kill(t);
    edit::TetShape s{0, std::numeric_limits<double>::infinity()};
    for (const auto& [c, tag] : p.add) {
      const auto& shape = e_.shape(e_.add(c, tag));
      s.max_amips = std::max(s.max_amips, shape.max_amips);
      s.min_scaled_jacobian = std::min(s.min_scaled_jacobian, shape.min_scaled_jacobian);
    }
    e_.rollback();
    return s;
  }

  StarLimits limits_for(const Proposal& p, double amips_cap) const {
    const auto old = old_star(e_, p);
    return {std::max(amips_cap, old.max_amips), std::min(o_.min_scaled_jacobian, old.min_scaled_jacobian)};
  }

  void count(const Proposal& p, bool is_collapse) {
    if (is_collapse) ++s_.collapses;
    else if (p.kill.size() == 2) ++s_.flips_2_3;
    else if (p.kill.size() == 3) ++s_.flips_3_2;
    else if (p.kill.size() == 4) ++s_.flips_4_4;
    else ++s_.edge_removals;
  }

  // Quality pass: worst tets first, the best operation on each.
  long quality_pass() {
    std::vector<int> bad;
    for (int t = 0; t < e_.num_slots(); ++t)
      if (e_.alive(t) && e_.shape(t).max_amips > o_.target_amips) bad.push_back(t);
    std::stable_sort(bad.begin(), bad.end(), [&](int a, int b) { return e_.shape(a).max_amips > e_.shape(b).max_amips; });
    if (static_cast<int>(bad.size()) > o_.max_quality_visits) bad.resize(o_.max_quality_visits);
    long done = 0;
    for (int t : bad) {
      if (!e_.alive(t)) continue;
      struct Candidate {
        Proposal p;
        bool is_collapse;
        double new_max;
      };
      std::vector<Candidate> candidates;
      const auto consider = [&](Proposal&& p, bool is_collapse) {
        const auto shape = preview(p);
        if (shape.max_amips < old_star(e_, p).max_amips) candidates.push_back({std::move(p), is_collapse, shape.max_amips});
      };
      const edit::Corners c = e_.corners(t);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const int u = c[i], v = c[j];
          Reject why;
          Proposal p;
          if (o_.collapse && edit::collapse(e_, u, v, p, &why)) consider(std::move(p), true);
          if (o_.collapse && edit::collapse(e_, v, u, p, &why)) consider(std::move(p), true);
          std::vector<Proposal> ring;
          if (o_.flip && edit::remove_edge(e_, u, v, ring, &why))
            for (auto& r : ring) consider(std::move(r), false);
        }
      for (int f = 0; f < 4 && o_.flip; ++f) {
        Reject why;
        Proposal p;
        if (edit::flip_face(e_, t, f, p, &why)) consider(std::move(p), false);
      }
      std::stable_sort(candidates.begin(), candidates.end(),
                       [](const Candidate& a, const Candidate& b) { return a.new_max < b.new_max; });
      for (const Candidate& k : candidates) {
        const auto old = old_star(e_, k.p);
        if (apply(k.p, {old.max_amips, std::min(o_.min_scaled_jacobian, old.min_scaled_jacobian)})) {
          count(k.p, k.is_collapse);
          ++done;
          break;
        }
      }
    }
    return done;
  }

  // Coarsening pass: collapses, shortest edge first.
  long collapse_pass() {
    struct Item {
      double length;
      int u, v;
    };
    std::vector<Item> edges;
    for (int t = 0; t < e_.num_slots(); ++t) {
      if (!e_.alive(t)) continue;
      const auto& c = e_.corners(t);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const int u = std::min(c[i], c[j]), v = std::max(c[i], c[j]);
          if (e_.frozen(u) && e_.frozen(v)) continue;
          edges.push_back({(e_.position(u) - e_.position(v)).norm(), u, v});
        }
    }
    std::sort(edges.begin(), edges.end(), [](const Item& a, const Item& b) {
      return a.length != b.length ? a.length < b.length : std::make_pair(a.u, a.v) < std::make_pair(b.u, b.v);
    });
    edges.erase(std::unique(edges.begin(), edges.end(),
                            [](const Item& a, const Item& b) { return a.u == b.u && a.v == b.v; }),
                edges.end());
    long done = 0;
    for (const Item& x : edges) {
      for (const auto& [a, b] : {std::pair{x.u, x.v}, std::pair{x.v, x.u}}) {
        if (e_.tets_of(a).empty() || e_.tets_of(b).empty()) break; // stale: an end collapsed already
        Proposal p;
        Reject why;
        if (!edit::collapse(e_, a, b, p, &why)) {
          if (why != Reject::frozen) ++s_.rejected[static_cast<int>(why)];
          continue;
        }
        if (apply(p, limits_for(p, o_.collapse_amips))) {
          count(p, true);
          ++done;
          break;
        }
      }
    }
    return done;
  }

 private:
  TetEditor& e_;
  const CurvedRemeshOptions& o_;
  CurvedRemeshStats& s_;
};

} // namespace

nlohmann::json CurvedRemeshStats::json() const {
  nlohmann::json rejections;
  for (int r = 0; r < edit::kRejectReasons; ++r) rejections[edit::to_string(static_cast<Reject>(r))] = rejected[r];
  return {{"tets_before", tets_before},
          {"tets_after", tets_after},
          {"max_amips_before", max_amips_before},
          {"max_amips_after", max_amips_after},
          {"mean_amips_before", mean_amips_before},
          {"mean_amips_after", mean_amips_after},
          {"min_scaled_jacobian_before", min_scaled_jacobian_before},
          {"min_scaled_jacobian_after", min_scaled_jacobian_after},
          {"collapses", collapses},
          {"flips_2_3", flips_2_3},
          {"flips_3_2", flips_3_2},
          {"flips_4_4", flips_4_4},
          {"edge_removals", edge_removals},
          {"vertex_moves", vertex_moves},
          {"node_moves", node_moves},
          {"rejected", rejections},
          {"rounds", rounds},
          {"seconds", seconds}};
}

CurvedRemeshStats remesh_curved(mesh::TetMesh& m, const CurvedRemeshOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  CurvedRemeshStats s;
  s.tets_before = m.num_tets();
  const Summary before = summarize(m);
  s.max_amips_before = before.max_amips;
  s.mean_amips_before = before.mean_amips;
  s.min_scaled_jacobian_before = before.min_scaled_jacobian;
  for (int round = 0; round < o.rounds; ++round) {
    long changed = 0;
    {
      TetEditor editor(m);
      Remesher r(editor, o, s);
      if (o.collapse || o.flip) changed += r.quality_pass();
      if (o.collapse) changed += r.collapse_pass();
      if (o.collapse || o.flip) changed += r.quality_pass();
      m = editor.to_mesh();
    }
    if (o.smooth) {
      const auto st = optimize_curved(m, o.smoothing);
      s.vertex_moves += st.vertex_moves;
      s.node_moves += st.node_moves;
      changed += st.vertex_moves + st.node_moves;
    }
    ++s.rounds;
    logger().debug("curved remesh round {}: {} tets, {} changes", round + 1, m.num_tets(), changed);
    if (changed == 0) break;
  }
  const Summary after = summarize(m);
  s.tets_after = m.num_tets();
  s.max_amips_after = after.max_amips;
  s.mean_amips_after = after.mean_amips;
  s.min_scaled_jacobian_after = after.min_scaled_jacobian;
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

} // namespace curvetet::volume

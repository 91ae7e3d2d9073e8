#include "curvetet/volume/optimize.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/highorder/quality.hpp"
#include "curvetet/volume/exact_optimizer.hpp"
#include "curvetet/volume/tet_amips.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <set>

namespace curvetet::volume::exact {

namespace {

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
  const int nt = o.num_tets();
  std::size_t flips = 0;
  for (int t = 0; t < nt; ++t) {
    if (!o.alive(t)) continue;
    if (o.tet_energy(t) < threshold || o.flips_known_to_fail(t)) continue;
    const auto q = o.tet(t);
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
  const std::size_t before = static_cast<std::size_t>(o.num_tets());
  std::size_t flips = 0;
  for (std::size_t t = 0; t < before; ++t) {
    if (!o.alive(static_cast<int>(t))) continue;
    const auto q = o.tet(static_cast<int>(t));
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
  for (int x : std::array<int, 4>(o.tet(t)))
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
    for (int k = 0; k < 4; ++k) x[k] = m.v.d[o.tet(t)[k]];
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
    const auto q = o.tet(t);
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
  const Tet& q = o.tet(t);
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
    return std::any_of(o.tet(t).begin(), o.tet(t).end(), [&](int x) { return !m.frozen[x]; });
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
    Tet q = o.tet(t);
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
        for (int x : std::array<int, 4>(o.tet(t))) any |= o.smooth_max(x);
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
  return worst >= 0 && std::all_of(o.tet(worst).begin(), o.tet(worst).end(), [&](int x) { return m.frozen[x]; });
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

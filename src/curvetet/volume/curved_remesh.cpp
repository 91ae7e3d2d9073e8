#include "curvetet/volume/curved_remesh.hpp"

#include "curvetet/core/log.hpp"
#include "curvetet/volume/curved_descent.hpp"
#include "curvetet/volume/edit/integer_hash.hpp"
#include "curvetet/volume/edit/operations.hpp"
#include "curvetet/volume/edit/tet_editor.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <unordered_map>

namespace curvetet::volume {
namespace {

using edit::Proposal;
using edit::Reject;
using edit::StarLimits;
using edit::TetEditor;

// Worst shape of the tets a proposal kills.
edit::TetShape old_star(const TetEditor& e, const Proposal& p) {
  edit::TetShape s{0, std::numeric_limits<double>::infinity()};
  for (int t : p.kill) {
    s.max_amips = std::max(s.max_amips, e.shape(t).max_amips);
    s.min_scaled_jacobian = std::min(s.min_scaled_jacobian, e.shape(t).min_scaled_jacobian);
  }
  return s;
}

edit::Corners with_vertex(edit::Corners c, int v) {
  std::replace(c.begin(), c.end(), edit::kNewVertex, v);
  return c;
}

constexpr int kPlacementLevels = 5;
constexpr std::size_t kCollapseTargets = 6;
using Vec3 = Eigen::Vector3d;

// Stages p in a transaction of editor e: its tets killed, its new vertex
// and tets added (returned).
std::vector<int> stage(TetEditor& e, const Proposal& p, int* new_vertex = nullptr) {
  e.begin();
  for (int t : p.kill) e.kill(t);
  const int v = p.adds_vertex ? e.add_vertex(p.new_vertex) : edit::kNewVertex;
  if (new_vertex) *new_vertex = v;
  std::vector<int> added;
  for (const auto& [c, tag] : p.add) added.push_back(e.add(with_vertex(c, v), tag));
  if (!p.straight_new_nodes) e.relax_new_nodes();
  return added;
}

// Max AMIPS of `tets`, or +inf once one reaches bound.
double star_max(const TetEditor& e, const std::vector<int>& tets, double bound) {
  double worst = 0;
  for (int t : tets) {
    if (!e.amips_below(t, bound)) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, e.shape(t).max_amips);
  }
  return worst;
}

// Pattern search over the 6 axis steps, halving from a quarter of the
// star's shortest edge; returns the best max AMIPS, *at its position.
double place_new_vertex(TetEditor& e, int v, const std::vector<int>& tets, Vec3& at, double worst, double bound) {
  double h = std::numeric_limits<double>::infinity();
  for (int w : e.neighbours(v)) h = std::min(h, (e.position(w) - e.position(v)).norm());
  h *= 0.25;
  for (int level = 0; level < kPlacementLevels; ++level, h *= 0.5) {
    bool improved = true;
    while (improved) {
      improved = false;
      for (int k = 0; k < 6; ++k) {
        const Vec3 d = (k % 2 ? -h : h) * Vec3::Unit(k / 2);
        e.move_new_vertex(v, d);
        const double m = star_max(e, tets, std::min(bound, worst));
        if (m < worst) {
          worst = m;
          improved = true;
          break;
        }
        e.move_new_vertex(v, -d);
      }
    }
  }
  at = e.position(v);
  return worst;
}

// preview() with p's own choice of new nodes.
double preview_as_is(TetEditor& e, Proposal& p, double bound) {
  int v = edit::kNewVertex;
  const std::vector<int> added = stage(e, p, &v);
  double worst = star_max(e, added, bound);
  if (p.adds_vertex) worst = place_new_vertex(e, v, added, p.new_vertex, worst, bound);
  e.rollback();
  return worst;
}

// Max AMIPS the new tets of p would have in editor e, or +inf once one
// reaches bound. A new vertex is first placed by a pattern search on that
// max (its place is kept in p). Where that fails, the split is tried again
// with its new nodes straight: a split of an ear's edge leaves a new tet on
// a nearly degenerate boundary triangle, which the relaxation's bending
// (spread from curved neighbours) turns inside out. e is left as it was.
double preview(TetEditor& e, Proposal& p, double bound) {
  const Vec3 start = p.new_vertex;
  const double worst = preview_as_is(e, p, bound);
  if (!p.adds_vertex || worst < bound) return worst;
  Proposal straight = p;
  straight.new_vertex = start;
  straight.straight_new_nodes = true;
  const double straight_worst = preview_as_is(e, straight, bound);
  if (!(straight_worst < worst)) return worst;
  p = std::move(straight);
  return straight_worst;
}

// Previews already made this round. A preview depends only on the
// proposal's tets and on the entities among their corners (the nodes the new
// tets reuse, the relaxation's fixed neighbours): node positions change only
// by commits here (the smoothing runs between rounds), and a commit that
// changes an entity among those corners adds tets at each of them, except at
// a collapsed vertex, whose tets (and so the proposal's) all die. So a
// preview of the same proposal under the same bound stands while no corner
// has been changed since. Neighbouring bad tets propose many of the same
// operations.
class PreviewMemo {
 public:
  std::optional<double> find(const Proposal& p, double bound, const std::vector<long>& changed_at) {
    if (p.adds_vertex) return std::nullopt; // its vertex's placement search is not memoized
    const auto it = known_.find(key(p, bound));
    if (it == known_.end()) return std::nullopt;
    for (int v : it->second.corners)
      if (v < static_cast<int>(changed_at.size()) && changed_at[v] > it->second.stamp) return std::nullopt;
    return it->second.new_max;
  }
  void remember(const Proposal& p, double bound, double new_max, long stamp) {
    if (p.adds_vertex) return;
    Entry& e = known_[key(p, bound)];
    e.new_max = new_max;
    e.stamp = stamp;
    e.corners.clear();
    for (const auto& [c, tag] : p.add) e.corners.insert(e.corners.end(), c.begin(), c.end());
    std::sort(e.corners.begin(), e.corners.end());
    e.corners.erase(std::unique(e.corners.begin(), e.corners.end()), e.corners.end());
  }

 private:
  struct Entry {
    double new_max = 0;
    long stamp = 0;           // commits made before the preview
    std::vector<int> corners; // of the new tets: those of the killed ones, but a collapsed vertex
  };
  static std::vector<std::int64_t> key(const Proposal& p, double bound) {
    std::vector<std::int64_t> k(p.kill.begin(), p.kill.end());
    k.push_back(-2);
    for (const auto& [c, tag] : p.add) {
      k.insert(k.end(), c.begin(), c.end());
      k.push_back(tag);
    }
    std::int64_t bits;
    std::memcpy(&bits, &bound, sizeof bits);
    k.push_back(bits);
    return k;
  }
  std::unordered_map<std::vector<std::int64_t>, Entry, edit::IntegerHash> known_;
};

class Remesher {
 public:
  Remesher(TetEditor& e, const CurvedRemeshOptions& o, CurvedRemeshStats& s)
      : e_(e), o_(o), s_(s), replicas_([this] { return Replica{e_, log_.size()}; }) {}

  // Runs p as a transaction; keeps it when every new tet passes the checks.
  bool apply(const Proposal& p, const StarLimits& limits) {
    stage(e_, p);
    if (const auto why = edit::check_new_tets(e_, limits)) {
      e_.rollback();
      ++s_.rejected[static_cast<int>(*why)];
      return false;
    }
    for (int t : e_.added())
      for (int v : e_.corners(t)) {
        if (v >= static_cast<int>(changed_at_.size())) changed_at_.resize(v + 1, 0);
        changed_at_[v] = ++commits_;
      }
    e_.commit();
    log_.push_back(p);
    return true;
  }

  // Whether a visit of tet t that failed before may now succeed: some
  // operation changed the star of one of its corners or of their
  // neighbours (the collapse targets) since.
  bool may_succeed_again(int t) const {
    const auto it = failed_at_.find(t);
    if (it == failed_at_.end()) return true;
    const auto changed_after = [&](int v) {
      return v < static_cast<int>(changed_at_.size()) && changed_at_[v] > it->second;
    };
    for (int c : e_.corners(t)) {
      if (changed_after(c)) return true;
      for (int w : e_.neighbours(c))
        if (changed_after(w)) return true;
    }
    return false;
  }

  StarLimits limits_for(const Proposal& p, double amips_cap) const {
    const auto old = old_star(e_, p);
    return {std::max(amips_cap, old.max_amips), std::min(o_.min_scaled_jacobian, old.min_scaled_jacobian)};
  }

  void count(const Proposal& p, bool is_collapse) {
    if (is_collapse) ++s_.collapses;
    else if (p.adds_vertex) ++s_.splits;
    else if (p.kill.size() == 2) ++s_.flips_2_3;
    else if (p.kill.size() == 3) ++s_.flips_3_2;
    else if (p.kill.size() == 4) ++s_.flips_4_4;
    else ++s_.edge_removals;
  }

  struct Candidate {
    Proposal p;
    bool is_collapse = false;
    StarLimits limits{}; // set by run_best
    double new_max = 0;
  };

  // Previews every candidate (in parallel, each on a replica of the
  // editor), then runs them best first (lowest new max AMIPS); keeps the
  // first whose new tets pass the checks under the limits the caller sets
  // for it (cap = the AMIPS a new tet may reach anyway).
  bool run_best(std::vector<Candidate>& candidates, double amips_cap) {
    std::vector<std::size_t> to_preview;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      candidates[k].limits = limits_for(candidates[k].p, amips_cap);
      if (const auto known = previews_.find(candidates[k].p, candidates[k].limits.max_amips, changed_at_))
        candidates[k].new_max = *known;
      else to_preview.push_back(k);
    }
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, to_preview.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          TetEditor& replica = up_to_date_replica();
          for (std::size_t j = r.begin(); j < r.end(); ++j) {
            Candidate& k = candidates[to_preview[j]];
            k.new_max = preview(replica, k.p, k.limits.max_amips);
          }
        },
        tbb::simple_partitioner());
    for (std::size_t k : to_preview)
      previews_.remember(candidates[k].p, candidates[k].limits.max_amips, candidates[k].new_max, commits_);
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.new_max < b.new_max; });
    for (const Candidate& k : candidates) {
      if (!(k.new_max < k.limits.max_amips)) break; // sorted: none of the rest fits either
      if (apply(k.p, k.limits)) {
        count(k.p, k.is_collapse);
        return true;
      }
    }
    return false;
  }

  // Collapses of free vertex v onto its kCollapseTargets nearest neighbours
  // (a far target rarely gives the best star, and every preview costs).
  void collapses_of(int v, std::vector<Candidate>& out) {
    if (e_.frozen(v)) return;
    std::vector<std::pair<double, int>> near;
    for (int w : e_.neighbours(v)) near.emplace_back((e_.position(w) - e_.position(v)).squaredNorm(), w);
    const auto keep = std::min<std::size_t>(near.size(), kCollapseTargets);
    std::partial_sort(near.begin(), near.begin() + keep, near.end());
    for (std::size_t k = 0; k < keep; ++k) {
      Proposal p;
      Reject why;
      if (edit::collapse(e_, v, near[k].second, p, &why)) out.push_back({std::move(p), true});
      else ++s_.rejected[static_cast<int>(why)];
    }
  }

  // Quality pass: worst tets first, the best operation on each (collapses
  // of its free corners onto any neighbour, removal of its edges, 2-3 flips
  // of its faces; else a split of one of its edges) if it lowers the star's
  // max AMIPS.
  long quality_pass(double threshold) {
    std::vector<int> bad;
    for (int t = 0; t < e_.num_slots(); ++t)
      if (e_.alive(t) && e_.shape(t).max_amips > threshold) bad.push_back(t);
    std::stable_sort(bad.begin(), bad.end(), [&](int a, int b) { return e_.shape(a).max_amips > e_.shape(b).max_amips; });
    if (static_cast<int>(bad.size()) > o_.max_quality_visits) bad.resize(o_.max_quality_visits);
    long done = 0;
    for (int t : bad) {
      if (!e_.alive(t) || !may_succeed_again(t)) continue;
      std::vector<Candidate> candidates;
      const edit::Corners c = e_.corners(t);
      for (int i = 0; i < 4 && o_.collapse; ++i) collapses_of(c[i], candidates);
      for (int i = 0; i < 4 && o_.flip; ++i)
        for (int j = i + 1; j < 4; ++j) {
          Reject why;
          std::vector<Proposal> ring;
          if (edit::remove_edge(e_, c[i], c[j], ring, &why))
            for (auto& r : ring) candidates.push_back({std::move(r), false});
        }
      for (int f = 0; f < 4 && o_.flip; ++f) {
        Reject why;
        Proposal p;
        if (edit::flip_face(e_, t, f, p, &why)) candidates.push_back({std::move(p), false});
      }
      if (run_best(candidates, 0)) {
        ++done;
        continue;
      }
      // Splits (the dearest: their vertex is placed by a search, and they
      // add tets) only for very bad tets where nothing else helps, or for
      // ears above ear_split_amips: a tet with two boundary faces has one
      // edge that is not on them, and only a new vertex on it gives each
      // face a tet of its own.
      const double amips = e_.shape(t).max_amips;
      if (amips <= o_.split_amips && !(amips > o_.ear_split_amips && boundary_faces(t) >= 2)) {
        failed_at_[t] = commits_;
        continue;
      }
      candidates.clear();
      for (int i = 0; i < 4 && o_.split; ++i)
        for (int j = i + 1; j < 4; ++j) {
          Reject why;
          Proposal p;
          if (edit::split(e_, c[i], c[j], p, &why)) candidates.push_back({std::move(p), false});
        }
      if (run_best(candidates, 0)) ++done;
      else failed_at_[t] = commits_;
    }
    return done;
  }

  int boundary_faces(int t) const {
    const edit::Corners& c = e_.corners(t);
    int n = 0;
    for (int f = 0; f < 4; ++f) n += e_.is_boundary_face(c[(f + 1) % 4], c[(f + 2) % 4], c[(f + 3) % 4]);
    return n;
  }

  // Coarsening pass: each free vertex, those with the shortest edge first,
  // collapses onto its best neighbour if the new tets stay under
  // collapse_amips (or under the old star's max AMIPS).
  long collapse_pass() {
    std::vector<std::pair<double, int>> order;
    for (int v = 0; v < e_.num_nodes(); ++v) {
      if (e_.frozen(v) || e_.tets_of(v).empty()) continue;
      double shortest = std::numeric_limits<double>::infinity();
      for (int w : e_.neighbours(v)) shortest = std::min(shortest, (e_.position(v) - e_.position(w)).norm());
      order.emplace_back(shortest, v);
    }
    std::sort(order.begin(), order.end());
    long done = 0;
    for (const auto& [length, v] : order) {
      if (e_.tets_of(v).empty()) continue;
      std::vector<Candidate> candidates;
      collapses_of(v, candidates);
      done += run_best(candidates, o_.collapse_amips);
    }
    return done;
  }

  // Coarsening by 3-2 flips: every interior edge with three tets around it
  // becomes a face (one tet fewer) if the two new tets stay under
  // target_amips, tets the quality pass leaves alone (or under the old
  // star's max AMIPS): flips up to collapse_amips left tets that the later
  // smoothing could not bring back under it (docs/usable_elements.md,
  // session 32).
  long flip_3_2_pass() {
    std::vector<std::pair<int, int>> edges;
    for (int t = 0; t < e_.num_slots(); ++t) {
      if (!e_.alive(t)) continue;
      const edit::Corners& c = e_.corners(t);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) edges.emplace_back(std::min(c[i], c[j]), std::max(c[i], c[j]));
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    long done = 0;
    for (const auto& [a, b] : edges) {
      if (!e_.has_edge(a, b) || edge_valence(a, b) != 3) continue;
      Reject why;
      std::vector<Proposal> ring;
      if (!edit::remove_edge(e_, a, b, ring, &why)) continue;
      std::vector<Candidate> candidates;
      for (auto& r : ring) candidates.push_back({std::move(r), false});
      done += run_best(candidates, o_.target_amips);
    }
    return done;
  }

  int edge_valence(int a, int b) const {
    int n = 0;
    for (int t : e_.tets_of(a)) {
      const edit::Corners& c = e_.corners(t);
      n += std::find(c.begin(), c.end(), b) != c.end();
    }
    return n;
  }

 private:
  // A copy of the editor for one thread's previews, with the number of
  // committed proposals it holds (it replays the rest before use, so it
  // matches e_ whatever thread it serves: the previews do not depend on the
  // thread count).
  struct Replica {
    TetEditor editor;
    std::size_t replayed = 0;
  };

  TetEditor& up_to_date_replica() {
    Replica& r = replicas_.local();
    for (; r.replayed < log_.size(); ++r.replayed) {
      stage(r.editor, log_[r.replayed]);
      r.editor.commit();
    }
    return r.editor;
  }

  TetEditor& e_;
  const CurvedRemeshOptions& o_;
  CurvedRemeshStats& s_;
  std::vector<Proposal> log_; // committed proposals, in order
  tbb::enumerable_thread_specific<Replica> replicas_;
  long commits_ = 0;
  std::vector<long> changed_at_;              // per vertex: the commit that last changed its star
  PreviewMemo previews_;
  std::unordered_map<int, long> failed_at_;   // per tet: commits_ when its visit last failed
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
          {"splits", splits},
          {"vertex_moves", vertex_moves},
          {"node_moves", node_moves},
          {"rejected", rejections},
          {"rounds", rounds},
          {"descent", descent.json()},
          {"seconds", seconds}};
}

CurvedRemeshStats remesh_curved(mesh::TetMesh& m, const CurvedRemeshOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  CurvedRemeshStats s;
  s.tets_before = m.num_tets();
  // Each tet's quality in m, kept up to date where m is measured anyway
  // (after each round's smoothing, by the descent).
  std::vector<highorder::TetQuality> per_tet = tet_qualities(m);
  const MeshQuality before = summarize(per_tet);
  s.max_amips_before = before.max_amips;
  s.mean_amips_before = before.mean_amips;
  s.min_scaled_jacobian_before = before.min_scaled_jacobian;
  // Smooths m and returns its quality.
  const auto smooth = [&] {
    if (o.smooth) {
      CurvedOptimizeOptions smoothing = o.smoothing;
      smoothing.measure = false;
      const auto st = optimize_curved(m, smoothing);
      s.vertex_moves += st.vertex_moves;
      s.node_moves += st.node_moves;
    }
    per_tet = tet_qualities(m);
    return summarize(per_tet);
  };
  MeshQuality last = before;
  for (int round = 0; round < o.rounds; ++round) {
    long changed = 0;
    const auto t0 = std::chrono::steady_clock::now();
    {
      TetEditor editor(m);
      Remesher r(editor, o, s);
      if (o.collapse || o.flip) changed += r.quality_pass(o.target_amips);
      if (o.collapse) changed += r.collapse_pass();
      if (o.flip) changed += r.flip_3_2_pass();
      // The coarsening's worst tets again (a collapse may leave one above
      // collapse_amips where the old star was worse).
      if (o.collapse || o.flip) changed += r.quality_pass(o.collapse_amips);
      m = editor.to_mesh();
    }
    const auto t1 = std::chrono::steady_clock::now();
    const MeshQuality now = smooth();
    ++s.rounds;
    logger().debug("curved remesh round {}: {} tets, {} operations ({:.2f} s), smoothing {:.2f} s, max AMIPS {:.4g}, "
                   "min scaled Jacobian {:.3g}",
                   round + 1, m.num_tets(), changed, std::chrono::duration<double>(t1 - t0).count(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(), now.max_amips,
                   now.min_scaled_jacobian);
    // Another round pays while this one changed enough tets and, where tets
    // above collapse_amips are left, lowered the max AMIPS (a round that
    // only raised the min scaled Jacobian rarely lowers the max in the
    // next); below collapse_amips the rounds coarsen.
    const bool gained = now.max_amips < (1 - o.smoothing.min_gain) * last.max_amips;
    last = now;
    if (changed < o.min_operations * m.num_tets() || (!gained && now.max_amips > o.collapse_amips)) break;
  }
  if (o.descend) s.descent = descend_curved(m, o.descent, &per_tet);
  const MeshQuality after = summarize(per_tet);
  s.tets_after = m.num_tets();
  s.max_amips_after = after.max_amips;
  s.mean_amips_after = after.mean_amips;
  s.min_scaled_jacobian_after = after.min_scaled_jacobian;
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

} // namespace curvetet::volume

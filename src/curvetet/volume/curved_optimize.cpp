#include "curvetet/volume/curved_optimize.hpp"

#include "curvetet/core/log.hpp"
#include "curvetet/highorder/amips_frames.hpp"
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quality.hpp"
#include "curvetet/volume/frame_cache.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace curvetet::volume {
namespace {

using Vec3 = Eigen::Vector3d;

// The nodes a move displaces (with their weight on the displacement) and the
// tets whose shape it changes.
struct Move {
  int key = -1; // the node the move is named after (corner v, or the node)
  bool corner = false;
  std::vector<std::pair<int, double>> nodes;
  std::vector<int> tets;
};

enum class Outcome { accepted, rejected_quality, rejected_certificate };

// Per-thread state of the move being tried (AmipsFrames): frames[k] (in the
// cache) and directions[k * q + q'] for touched tet k.
struct Scratch {
  std::vector<Eigen::Matrix3d*> frames;
  std::vector<Eigen::Vector3d> directions;
  // The trials' AMIPS terms on the order-2P lattice, per touched tet, made
  // when a trial first reaches the tet.
  std::vector<highorder::AmipsFrames::RankOneTerms> terms;
  std::vector<char> has_terms;
};

constexpr std::size_t kBatchSize = 64; // moves tried in parallel at once
constexpr std::size_t kCompassTries = 3; // certificates tried for the compass search's best steps

// The 26 unit directions towards the neighbours of a cube's centre.
const std::vector<Eigen::Vector3d>& compass_directions() {
  static const std::vector<Eigen::Vector3d> dirs = [] {
    std::vector<Eigen::Vector3d> out;
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int k = -1; k <= 1; ++k)
          if (i || j || k) out.push_back(Eigen::Vector3d(i, j, k).normalized());
    return out;
  }();
  return dirs;
}

// What a sweep improves: the max AMIPS of the touched tets, or their min
// scaled Jacobian (kept from getting worse by the other goal's moves).
enum class Goal { amips, scaled_jacobian };

class CurvedOptimizer {
 public:
  CurvedOptimizer(mesh::TetMesh& m, const CurvedOptimizeOptions& o)
      : m_(m), o_(o), np_(m.tet_nodes()), table_(highorder::amips_frames(m.order)), q_(table_.num_points()),
        cache_(m.num_tets(), q_, o.frame_cache_bytes) {
    const int n = static_cast<int>(m.nodes.size());
    frozen_.assign(n, 0);
    for (int id : m.boundary) frozen_[id] = 1;
    freeze_hull();
    // node -> (tet, local index), CSR.
    offset_.assign(n + 1, 0);
    for (int id : m.tets) ++offset_[id + 1];
    std::partial_sum(offset_.begin(), offset_.end(), offset_.begin());
    uses_.resize(m.tets.size());
    std::vector<int> fill(offset_.begin(), offset_.end() - 1);
    for (int t = 0; t < m.num_tets(); ++t)
      for (int i = 0; i < np_; ++i) {
        const int id = m.tet(t)[i];
        uses_[fill[id]++] = {t, i};
      }
    for (int i = 0; i < np_; ++i) barycentric_.push_back(highorder::tet_node_barycentric(m.order, i));
    for (auto& f : failed_at_) f.assign(n, -1);
    changed_at_.assign(m.num_tets(), 0);
    amips_.assign(m.num_tets(), 0);
    sj_.assign(m.num_tets(), 0);
    // The first tets that fit are cached right away (slots in tet order).
    const int cached = std::min(m.num_tets(), cache_.capacity());
    cache_.reserve(cached);
    for (int t = 0; t < cached; ++t) cache_.slot(t);
    tbb::parallel_for(0, m_.num_tets(), [&](int t) {
      std::vector<Eigen::Matrix3d> scratch;
      if (t >= cached) scratch.resize(q_);
      evaluate(t, t < cached ? cache_.slot(t) : scratch.data());
    });
  }

  const std::vector<double>& amips() const { return amips_; }
  const std::vector<double>& scaled_jacobians() const { return sj_; }

  // One sweep over the bad tets, worst first: max AMIPS >= threshold, or
  // min scaled Jacobian below options.raise_scaled_jacobian_below (the worst
  // options.max_bad_tets of them). Every node of a
  // bad tet is a candidate move, once per sweep; the candidates go in
  // batches of moves with disjoint touched tets, which are tried in
  // parallel: a move reads and writes only its touched tets and nodes (a
  // node a move displaces lies in its touched tets only), so each move sees
  // the mesh as the previous batches left it, whatever the thread count.
  // A candidate that conflicts with the batch waits for the next one.
  void sweep(Goal goal, double threshold, CurvedOptimizeStats& stats) {
    const auto is_bad = [&](int t) {
      return goal == Goal::amips ? amips_[t] >= threshold : sj_[t] < o_.raise_scaled_jacobian_below;
    };
    const auto badness = [&](int t) { return goal == Goal::amips ? amips_[t] : -sj_[t]; };
    sweep_max_amips_ = *std::max_element(amips_.begin(), amips_.end());
    std::vector<int> bad;
    for (int t = 0; t < m_.num_tets(); ++t)
      if (is_bad(t)) bad.push_back(t);
    std::stable_sort(bad.begin(), bad.end(), [&](int a, int b) { return badness(a) > badness(b); });
    if (bad.size() > o_.max_bad_tets) bad.resize(o_.max_bad_tets);
    // Candidates (bad tet, local node) in order; each node once.
    std::vector<std::pair<int, int>> pending;
    std::vector<char> listed(m_.nodes.size(), 0);
    for (int t : bad)
      for (int i = 0; i < np_; ++i) {
        const int id = m_.tet(t)[i];
        if (frozen_[id] || listed[id] || !(i < 4 ? o_.move_vertices : o_.move_nodes)) continue;
        listed[id] = 1;
        pending.emplace_back(t, i);
      }

    std::vector<long> locked(m_.num_tets(), -1); // batch that holds a tet
    struct Job {
      Move mv;
      Outcome outcome = Outcome::rejected_quality;
    };
    std::vector<Job> batch;
    while (!pending.empty()) {
      ++clock_;
      batch.clear();
      std::vector<std::pair<int, int>> later;
      for (std::size_t c = 0; c < pending.size(); ++c) {
        const auto [t, i] = pending[c];
        if (batch.size() >= kBatchSize) {
          later.insert(later.end(), pending.begin() + c, pending.end());
          break;
        }
        if (!is_bad(t)) continue; // improved by an earlier move
        const int id = m_.tet(t)[i];
        Move mv = i < 4 ? vertex_move(id) : node_move(id);
        if (mv.nodes.empty()) continue;
        if (std::any_of(mv.tets.begin(), mv.tets.end(), [&](int x) { return locked[x] == clock_; })) {
          later.emplace_back(t, i);
          continue;
        }
        // Moving one high-order node of a straight tet changes its Jacobian
        // by d (x) grad(phi_node), whose sign varies over the tet, so its
        // true max AMIPS rises (a dip of the max sampled at the lattice
        // points is an artefact): only try when the worst touched tet is curved.
        if (i >= 4 && straight(worst_of(mv.tets))) continue;
        // A move depends only on its touched tets: if none changed since it
        // last failed for this goal, it would fail again.
        long last_change = -1;
        for (int x : mv.tets) last_change = std::max(last_change, changed_at_[x]);
        if (last_change < failed_at_[static_cast<int>(goal)][id]) continue;
        for (int x : mv.tets) locked[x] = clock_;
        batch.push_back({std::move(mv)});
      }
      pending.swap(later);
      if (batch.empty()) continue;

      // Frames of every touched tet in the cache before the parallel part
      // (the cache's bookkeeping is not shared between threads).
      std::size_t touched = 0;
      for (const Job& j : batch) touched += j.mv.tets.size();
      cache_.reserve(static_cast<int>(touched));
      std::vector<int> missing;
      for (const Job& j : batch)
        for (int x : j.mv.tets)
          if (!cache_.cached(x)) {
            cache_.slot(x);
            missing.push_back(x);
          }
      tbb::parallel_for(std::size_t(0), missing.size(), [&](std::size_t k) { frames(missing[k], cache_.slot(missing[k])); });

      // One move per task: a corner's compass search costs a hundred node
      // moves, so chunks of moves would leave a thread idle at the end.
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, batch.size(), 1),
          [&](const tbb::blocked_range<std::size_t>& r) {
            thread_local Scratch scratch;
            for (std::size_t k = r.begin(); k < r.end(); ++k) batch[k].outcome = try_move(batch[k].mv, goal, scratch);
          },
          tbb::simple_partitioner());
      for (const Job& j : batch) {
        switch (j.outcome) {
          case Outcome::accepted:
            ++(j.mv.corner ? stats.vertex_moves : stats.node_moves);
            if (goal == Goal::scaled_jacobian) ++stats.scaled_jacobian_moves;
            for (int x : j.mv.tets) changed_at_[x] = clock_;
            break;
          case Outcome::rejected_quality: ++stats.rejected_quality; break;
          case Outcome::rejected_certificate: ++stats.rejected_certificate; break;
        }
        if (j.outcome != Outcome::accepted) failed_at_[static_cast<int>(goal)][j.mv.key] = clock_;
      }
    }
  }

 private:
  // Whether every node of tet t is where its corners' affine map puts it
  // (then its Jacobian is constant).
  bool straight(int t) const {
    const int* ids = m_.tet(t);
    const Vec3 &a = m_.nodes[ids[0]], &b = m_.nodes[ids[1]], &c = m_.nodes[ids[2]], &d = m_.nodes[ids[3]];
    const double scale = std::max({(b - a).cwiseAbs().maxCoeff(), (c - a).cwiseAbs().maxCoeff(),
                                   (d - a).cwiseAbs().maxCoeff()});
    for (int i = 4; i < np_; ++i) {
      const auto& w = barycentric_[i];
      const Vec3 affine = w[0] * a + w[1] * b + w[2] * c + w[3] * d;
      if ((m_.nodes[ids[i]] - affine).cwiseAbs().maxCoeff() > 1e-12 * scale) return false;
    }
    return true;
  }

  // Frames of tet t from its nodes, into k[0, q_).
  void frames(int t, Eigen::Matrix3d* k) const {
    Vec3 nodes[165]; // order <= 8
    m_.tet_positions(t, nodes);
    table_.frames(nodes, k);
  }

  // Refreshes tet t's frames (into k) and amips_[t], sj_[t] (every sample
  // of the convention, as reported). From the nodes, so that the frames do
  // not depend on whether the cache kept them.
  void evaluate(int t, Eigen::Matrix3d* k) {
    frames(t, k);
    amips_[t] = table_.max_amips(k, nullptr, Vec3::Zero());
    sj_[t] = table_.min_scaled_jacobian(k, nullptr, Vec3::Zero());
  }

  bool certified(int t) const {
    Vec3 nodes[165];
    m_.tet_positions(t, nodes);
    return highorder::certify_tet(m_.order, nodes).validity == highorder::Validity::positive;
  }

  // Corner v and the star's nodes weighted by their barycentric weight on v.
  // Empty when a node with a non-zero weight is frozen.
  Move vertex_move(int v) const {
    Move mv;
    mv.key = v;
    mv.corner = true;
    for (int k = offset_[v]; k < offset_[v + 1]; ++k) {
      const auto [t, local] = uses_[k];
      mv.tets.push_back(t);
      for (int i = 0; i < np_; ++i) {
        const double w = barycentric_[i][local];
        if (w == 0) continue;
        const int id = m_.tet(t)[i];
        if (frozen_[id]) return {};
        mv.nodes.emplace_back(id, w);
      }
    }
    std::sort(mv.nodes.begin(), mv.nodes.end());
    mv.nodes.erase(std::unique(mv.nodes.begin(), mv.nodes.end(),
                               [](const auto& a, const auto& b) { return a.first == b.first; }),
                   mv.nodes.end());
    std::sort(mv.tets.begin(), mv.tets.end());
    mv.tets.erase(std::unique(mv.tets.begin(), mv.tets.end()), mv.tets.end());
    return mv;
  }

  // Nodes of tet faces used once (the hull) are frozen too, listed or not.
  void freeze_hull() {
    std::vector<std::pair<std::array<int, 3>, std::pair<int, int>>> faces;
    for (int t = 0; t < m_.num_tets(); ++t)
      for (int f = 0; f < 4; ++f) {
        std::array<int, 3> key;
        for (int k = 0; k < 3; ++k) key[k] = m_.tet(t)[highorder::kTetFaces[f][k]];
        std::sort(key.begin(), key.end());
        faces.push_back({key, {t, f}});
      }
    std::sort(faces.begin(), faces.end());
    for (std::size_t i = 0; i < faces.size();) {
      std::size_t j = i + 1;
      while (j < faces.size() && faces[j].first == faces[i].first) ++j;
      if (j == i + 1)
        for (int node : highorder::tet_face_nodes(m_.order, faces[i].second.second))
          frozen_[m_.tet(faces[i].second.first)[node]] = 1;
      i = j;
    }
  }

  int worst_of(const std::vector<int>& tets) const {
    return *std::max_element(tets.begin(), tets.end(), [&](int a, int b) { return amips_[a] < amips_[b]; });
  }

  Move node_move(int id) const {
    Move mv;
    mv.key = id;
    mv.nodes.emplace_back(id, 1.0);
    for (int k = offset_[id]; k < offset_[id + 1]; ++k) mv.tets.push_back(uses_[k].first);
    std::sort(mv.tets.begin(), mv.tets.end());
    mv.tets.erase(std::unique(mv.tets.begin(), mv.tets.end()), mv.tets.end());
    return mv;
  }

  // The move's frames (already cached, see sweep) and rank-one directions.
  void prepare(const Move& mv, Scratch& x) {
    x.frames.clear();
    for (int t : mv.tets) x.frames.push_back(cache_.cached_frames(t));
    x.directions.assign(mv.tets.size() * q_, Vec3::Zero());
    x.terms.resize(mv.tets.size() * table_.num_lattice_points());
    x.has_terms.assign(mv.tets.size(), 0);
    for (std::size_t k = 0; k < mv.tets.size(); ++k)
      for (int i = 0; i < np_; ++i) {
        const int id = m_.tet(mv.tets[k])[i];
        const auto it = std::lower_bound(mv.nodes.begin(), mv.nodes.end(), std::make_pair(id, -std::numeric_limits<double>::infinity()));
        if (it != mv.nodes.end() && it->first == id) table_.add_direction(i, it->second, &x.directions[k * q_]);
      }
  }

  // Max AMIPS of the touched tets mv.tets[k], k in `which`, were the move's
  // nodes displaced by d, on the order-2P lattice (the trials); stops early
  // (returning a value >= bound) once a tet reaches `bound`.
  double trial_amips(Scratch& x, const std::vector<int>& which, const Vec3& d,
                     double bound = std::numeric_limits<double>::infinity()) const {
    const int lattice = table_.num_lattice_points();
    double worst = 0;
    for (int k : which) {
      highorder::AmipsFrames::RankOneTerms* terms = &x.terms[static_cast<std::size_t>(k) * lattice];
      if (!x.has_terms[k]) {
        table_.rank_one_terms(x.frames[k], &x.directions[k * q_], terms, lattice);
        x.has_terms[k] = 1;
      }
      worst = std::max(worst, table_.max_amips(terms, d, bound, lattice));
      if (worst >= bound) break;
    }
    return worst;
  }

  // Min scaled Jacobian of the same tets on the same lattice; stops early
  // (returning a value < floor) once a tet falls below `floor`.
  double trial_scaled_jacobian(const Scratch& x, const std::vector<int>& which, const Vec3& d,
                               double floor = -std::numeric_limits<double>::infinity()) const {
    double worst = std::numeric_limits<double>::infinity();
    for (int k : which) {
      worst = std::min(worst, table_.min_scaled_jacobian(x.frames[k], &x.directions[k * q_], d, floor,
                                                         table_.num_lattice_points()));
      if (worst < floor) break;
    }
    return worst;
  }

  void place(const Move& mv, const std::vector<Vec3>& saved, const Vec3& d) {
    for (std::size_t k = 0; k < mv.nodes.size(); ++k) m_.nodes[mv.nodes[k].first] = saved[k] + mv.nodes[k].second * d;
  }

  // Shortest and longest corner edges of the touched tets: the range of
  // the step lengths (a thin tet next to big ones may need a long move).
  std::pair<double, double> edge_range(const Move& mv) const {
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (int t : mv.tets)
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) {
          const double e = (m_.nodes[m_.tet(t)[a]] - m_.nodes[m_.tet(t)[b]]).norm();
          lo = std::min(lo, e);
          hi = std::max(hi, e);
        }
    return {lo, hi};
  }

  // Tries the move along a descent direction of the goal with halving
  // steps; keeps the first step that improves the goal without hurting the
  // other measure and whose touched tets are all certified positive (for a
  // corner, then the best compass steps).
  Outcome try_move(const Move& mv, Goal goal, Scratch& x) {
    double amips0 = 0, sj0 = std::numeric_limits<double>::infinity();
    for (int t : mv.tets) {
      amips0 = std::max(amips0, amips_[t]);
      sj0 = std::min(sj0, sj_[t]);
    }
    const auto [h, h_max] = edge_range(mv);
    if (!(h > 0) || !std::isfinite(amips0)) return Outcome::rejected_quality;
    prepare(mv, x);

    // The touched tets, worst for the goal first (the trials stop at the
    // first tet past their bound), and those that decide the direction:
    // those near the worst.
    std::vector<int> all(mv.tets.size()), active;
    std::iota(all.begin(), all.end(), 0);
    std::stable_sort(all.begin(), all.end(), [&](int a, int b) {
      const int s = mv.tets[a], t = mv.tets[b];
      return goal == Goal::amips ? amips_[s] > amips_[t] : sj_[s] < sj_[t];
    });
    for (int k : all) {
      const int t = mv.tets[k];
      if (goal == Goal::amips ? amips_[t] >= 0.5 * amips0 : sj_[t] < o_.min_scaled_jacobian) active.push_back(k);
    }
    // Descent direction: the gradient of the goal's measure at its worst
    // point among the active tets (the max's gradient where that point is
    // unique).
    const int lattice_points = table_.num_lattice_points();
    int worst_k = -1, worst_q = -1;
    double worst = goal == Goal::amips ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    for (int k : active) {
      double value = 0;
      const int q = goal == Goal::amips ? table_.worst_amips_point(x.frames[k], lattice_points, &value)
                                        : table_.worst_scaled_jacobian_point(x.frames[k], lattice_points, &value);
      if (goal == Goal::amips ? value > worst : value < worst) {
        worst = value;
        worst_k = k;
        worst_q = q;
      }
    }
    if (worst_k < 0 || !std::isfinite(worst)) return Outcome::rejected_quality;
    const Eigen::Matrix3d& k_worst = x.frames[worst_k][worst_q];
    const Vec3& c_worst = x.directions[worst_k * q_ + worst_q];
    const Vec3 g = goal == Goal::amips ? table_.amips_gradient(k_worst, c_worst)
                                       : Vec3(-table_.scaled_jacobian_gradient(k_worst, c_worst));
    if (!(g.norm() > 0) || !g.allFinite()) return Outcome::rejected_quality;
    const Vec3 dir = -g.normalized();

    // AMIPS moves must lower the max and may not take a tet below the scaled
    // Jacobian floor; scaled-Jacobian moves must raise the min and may not
    // raise the mesh's max AMIPS (as it was when the sweep began).
    const double amips_bound = goal == Goal::amips ? amips0 * (1 - 1e-6) : sweep_max_amips_;
    const double sj_floor = goal == Goal::amips ? std::min(sj0, o_.min_scaled_jacobian) : sj0 * (1 + 1e-6);
    // The goal's value at d under the constraints above (lower is better),
    // or +inf where a constraint fails or the value is not below `cutoff`.
    const double inf = std::numeric_limits<double>::infinity();
    const auto constrained = [&](const Vec3& d, double cutoff = std::numeric_limits<double>::infinity()) {
      const double a_bound = goal == Goal::amips ? std::min(amips_bound, cutoff) : amips_bound;
      const double a = trial_amips(x, all, d, a_bound);
      if (!(a < a_bound)) return inf;
      const double floor = goal == Goal::amips ? sj_floor : std::max(sj_floor, -cutoff);
      const double sj = trial_scaled_jacobian(x, all, d, floor);
      if (goal == Goal::amips ? sj < floor : !(sj > floor)) return inf;
      return goal == Goal::amips ? a : -sj;
    };
    std::vector<Vec3> saved;
    for (const auto& [id, w] : mv.nodes) saved.push_back(m_.nodes[id]);
    bool certificate_failed = false;
    // Keeps d when the touched tets meet the constraints at every sample of
    // the convention (so what is reported is what is optimized) and are
    // certified positive. Only for a d whose trial passed: its order-2P
    // lattice is already known to meet the scaled-Jacobian constraint (same
    // sums, same or stricter bounds), so that check starts after it; the
    // trials' AMIPS came from the rank-one terms (other roundings), so
    // AMIPS is checked again on every sample.
    const int lattice = table_.num_lattice_points();
    const auto accept_at = [&](const Vec3& d) {
      for (int k : all) {
        const Vec3* c = &x.directions[k * q_];
        if (!(table_.max_amips(x.frames[k], c, d, amips_bound) < amips_bound)) return false;
        const double sj = table_.min_scaled_jacobian(x.frames[k], c, d, sj_floor, -1, lattice);
        if (goal == Goal::amips ? sj < sj_floor : !(sj > sj_floor)) return false;
      }
      place(mv, saved, d);
      bool ok = true;
      for (int t : mv.tets) ok = ok && certified(t);
      if (!ok) {
        certificate_failed = true;
        place(mv, saved, Vec3::Zero()); // saved + 0 * d: bit-exact restore
        return false;
      }
      for (std::size_t k = 0; k < mv.tets.size(); ++k) evaluate(mv.tets[k], x.frames[k]);
      return true;
    };
    // Halving steps from a quarter of the longest edge down to the shortest
    // edge's quarter halved line_search_steps - 1 times.
    const double smallest = 0.25 * h * std::pow(0.5, o_.line_search_steps - 1);
    for (double step = 0.25 * h_max; step >= smallest; step *= 0.5)
      if (std::isfinite(constrained(step * dir)) && accept_at(step * dir)) return Outcome::accepted;

    // The max over samples is not smooth: where the descent direction of a
    // corner is stuck at a kink, the best of a fixed set of directions and
    // the same steps often is not (certified best first, a few tries). Node
    // moves skip it: they are many and rarely the limit.
    const auto rejected = [&] { return certificate_failed ? Outcome::rejected_certificate : Outcome::rejected_quality; };
    if (!mv.corner) return rejected();
    // The kCompassTries best steps, best first (a step no better than the
    // last kept is cut short by the trials' bound).
    std::vector<std::pair<double, Vec3>> best;
    for (double step = 0.25 * h_max; step >= smallest; step *= 0.5)
      for (const Vec3& u : compass_directions()) {
        const double value = constrained(step * u, best.size() < kCompassTries ? inf : best.back().first);
        if (!std::isfinite(value)) continue;
        const auto at = std::upper_bound(best.begin(), best.end(), value,
                                         [](double v, const auto& b) { return v < b.first; });
        best.insert(at, {value, step * u});
        if (best.size() > kCompassTries) best.pop_back();
      }
    for (const auto& [value, d] : best)
      if (accept_at(d)) return Outcome::accepted;
    return rejected();
  }

  mesh::TetMesh& m_;
  const CurvedOptimizeOptions& o_;
  const int np_;
  std::vector<char> frozen_; // nodes of listed boundary triangles
  std::vector<int> offset_;
  std::vector<std::pair<int, int>> uses_;
  std::vector<std::array<double, 4>> barycentric_; // of each local node
  const highorder::AmipsFrames& table_;
  const int q_; // sample points per tet (highorder::quality_samples)
  std::vector<double> amips_;           // max AMIPS per tet
  std::vector<double> sj_;              // min scaled Jacobian per tet
  FrameCache cache_;
  double sweep_max_amips_ = 0;
  long clock_ = 0;                             // batches tried so far
  std::vector<long> changed_at_;               // per tet: batch of the last move that changed it
  std::array<std::vector<long>, 2> failed_at_; // per goal and node: batch where its move last failed
};

} // namespace

std::vector<highorder::TetQuality> tet_qualities(const mesh::TetMesh& m) {
  std::vector<highorder::TetQuality> q(m.num_tets());
  tbb::parallel_for(0, m.num_tets(), [&](int t) {
    std::vector<Vec3> nodes(m.tet_nodes());
    m.tet_positions(t, nodes.data());
    q[t] = highorder::tet_quality(m.order, nodes.data());
  });
  return q;
}

MeshQuality summarize(const std::vector<highorder::TetQuality>& q) {
  const double n = static_cast<double>(q.size());
  MeshQuality s;
  s.min_scaled_jacobian = q.empty() ? 0 : std::numeric_limits<double>::infinity();
  for (const auto& x : q) {
    s.max_amips = std::max(s.max_amips, x.max_amips);
    s.mean_amips += x.mean_amips / n;
    s.min_scaled_jacobian = std::min(s.min_scaled_jacobian, x.min_scaled_jacobian);
  }
  return s;
}

MeshQuality mesh_quality(const mesh::TetMesh& m) { return summarize(tet_qualities(m)); }

CurvedOptimizeStats optimize_curved(mesh::TetMesh& m, const CurvedOptimizeOptions& o) {
  CurvedOptimizeStats stats;
  if (o.measure) {
    const MeshQuality before = mesh_quality(m);
    stats.max_amips_before = before.max_amips;
    stats.mean_amips_before = before.mean_amips;
    stats.min_scaled_jacobian_before = before.min_scaled_jacobian;
  }
  if (m.num_tets() > 0) {
    CurvedOptimizer opt(m, o);
    const auto max_amips = [&] { return *std::max_element(opt.amips().begin(), opt.amips().end()); };
    const auto min_sj = [&] { return *std::min_element(opt.scaled_jacobians().begin(), opt.scaled_jacobians().end()); };
    for (int pass = 0; pass < o.passes; ++pass) {
      std::vector<double> sorted = opt.amips();
      const std::size_t k = std::min({sorted.size() - 1, static_cast<std::size_t>(o.bad_fraction * sorted.size()),
                                      std::max<std::size_t>(o.max_bad_tets, 1) - 1});
      std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end(), std::greater<>());
      const double threshold = std::max(o.min_amips, sorted[k]);
      const int moves = stats.vertex_moves + stats.node_moves;
      const double amips_before = max_amips(), sj_before = min_sj();
      opt.sweep(Goal::amips, threshold, stats);
      opt.sweep(Goal::scaled_jacobian, threshold, stats);
      ++stats.passes;
      const double amips_now = max_amips(), sj_now = min_sj();
      logger().debug("curved optimization pass {}: max AMIPS {:.4g}, min scaled Jacobian {:.3g}, {} moves", pass + 1,
                     amips_now, sj_now, stats.vertex_moves + stats.node_moves - moves);
      // Stop once a pass changes neither extreme by more than min_gain.
      if (amips_now > (1 - o.min_gain) * amips_before && sj_now < (1 + o.min_gain) * sj_before) break;
    }
  }
  if (o.measure) {
    const MeshQuality after = mesh_quality(m);
    stats.max_amips_after = after.max_amips;
    stats.mean_amips_after = after.mean_amips;
    stats.min_scaled_jacobian_after = after.min_scaled_jacobian;
  }
  return stats;
}

} // namespace curvetet::volume

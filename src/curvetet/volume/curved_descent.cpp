#include "curvetet/volume/curved_descent.hpp"

#include "curvetet/core/log.hpp"
#include "curvetet/highorder/amips_frames.hpp"
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quality.hpp"
#include "curvetet/volume/descent_terms.hpp"

#include <Eigen/Dense>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <vector>

namespace curvetet::volume {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kRounds = 4; // optimizations, each holding the tets the previous one could not keep

// Nodes that never move: those of listed boundary triangles and of hull
// faces (faces of one tet).
std::vector<char> pinned_nodes(const mesh::TetMesh& m) {
  std::vector<char> pinned(m.nodes.size(), 0);
  for (int id : m.boundary) pinned[id] = 1;
  const int np = m.tet_nodes();
  std::map<std::array<int, 3>, std::pair<int, int>> uses; // sorted corners -> (count, tet * 4 + face)
  for (int t = 0; t < m.num_tets(); ++t)
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> key;
      for (int k = 0; k < 3; ++k) key[k] = m.tets[t * np + highorder::kTetFaces[f][k]];
      std::sort(key.begin(), key.end());
      auto& u = uses[key];
      ++u.first;
      u.second = t * 4 + f;
    }
  for (const auto& [key, u] : uses)
    if (u.first == 1)
      for (int i : highorder::tet_face_nodes(m.order, u.second % 4)) pinned[m.tets[(u.second / 4) * np + i]] = 1;
  return pinned;
}

// E and dE/dx over the free nodes (see the header). Per-tet terms in
// parallel, summed in tet order.
class Energy {
 public:
  Energy(mesh::TetMesh& m, const std::vector<int>& free_index, int num_free, int power, double gradient_share)
      : m_(m), free_(free_index), num_free_(num_free),
        gradient_share_(gradient_share),
        frames_(highorder::amips_frames(m.order)),
        points_(frames_.num_lattice_points()), np_(m.tet_nodes()), term_(m.num_tets()),
        worst_(m.num_tets(), 0), has_gradient_(m.num_tets(), 0), grad_(static_cast<std::size_t>(m.num_tets()) * np_) {
    for (int t = 0; t < m.num_tets(); ++t)
      for (int i = 0; i < np_; ++i)
        if (free_[m.tets[t * np_ + i]] >= 0) {
          tets_.push_back(t);
          break;
        }
    // The references: the worst AMIPS and scaled Jacobian at the start.
    std::vector<double> worst_sj(m.num_tets(), kInf);
    for_tets([&](int t, std::vector<Mat3>& k, std::vector<Mat3>&, std::vector<Vec3>&) {
      double w = 0;
      for (int q = 0; q < points_; ++q) {
        w = std::max(w, amips(k[q]));
        worst_sj[t] = std::min(worst_sj[t], frames_.min_scaled_jacobian(&k[q], nullptr, Vec3::Zero(), -kInf, 1));
      }
      term_[t] = w;
    });
    double worst = 0, least_sj = kInf;
    for (int t : tets_) {
      worst = std::max(worst, term_[t]);
      least_sj = std::min(least_sj, worst_sj[t]);
    }
    terms_.amips_ref = std::isfinite(worst) && worst > 0 ? worst : 1;
    terms_.sj_ref = least_sj > 0 && std::isfinite(least_sj) ? least_sj : 1;
    terms_.edges = frames_.edges();
    terms_.reference_det = frames_.reference_to_regular().determinant();
    terms_.power = power;
  }

  int points() const { return static_cast<int>(tets_.size()) * points_; }
  bool partial_gradients() const { return gradient_share_ > 0; }
  void use_every_gradient() { gradient_share_ = 0; }
  // After a finite evaluation: the largest of AMIPS / A0 and sJ0 / scaled
  // Jacobian over its points (E's limit as p grows, up to the power).
  double worst() const {
    double w = 0;
    for (int t : tets_) w = std::max(w, worst_[t]);
    return w;
  }
  // Per free coordinate, the least h^2 over the tets with that node, h a
  // tet's mean corner edge: E is scale-free, so its curvature in a node
  // goes as 1 / h^2, and the smallest tet around a node bounds its step.
  Eigen::VectorXd inverse_curvature() const {
    Eigen::VectorXd c = Eigen::VectorXd::Constant(3 * num_free_, kInf);
    for (int t : tets_) {
      const int* v = &m_.tets[t * np_];
      double h = 0;
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) h += (m_.nodes[v[a]] - m_.nodes[v[b]]).norm() / 6;
      for (int i = 0; i < np_; ++i)
        if (const int f = free_[v[i]]; f >= 0) c.segment<3>(3 * f) = c.segment<3>(3 * f).cwiseMin(h * h);
    }
    return c;
  }
  void set(const Eigen::VectorXd& x) {
    for (std::size_t n = 0; n < free_.size(); ++n)
      if (free_[n] >= 0) m_.nodes[n] = x.segment<3>(3 * free_[n]);
  }
  Eigen::VectorXd get() const {
    Eigen::VectorXd x(3 * num_free_);
    for (std::size_t n = 0; n < free_.size(); ++n)
      if (free_[n] >= 0) x.segment<3>(3 * free_[n]) = m_.nodes[n];
    return x;
  }

  // E at the mesh's current nodes (+inf where a point is not positive);
  // with `grad`, also its gradient.
  double operator()(Eigen::VectorXd* grad) {
    infinite_ = false;
    // The tets whose terms made together less than gradient_share of E at
    // the last evaluation get no gradient (their share of it is as small,
    // and they are most of the moved tets); their terms still count in E,
    // and +inf keeps every iterate positive.
    const double floor = grad ? gradient_floor() : kInf;
    for_tets([&](int t, std::vector<Mat3>& k, std::vector<Mat3>& dk, std::vector<Vec3>& g) {
      const bool with_gradient = grad && term_[t] >= floor;
      double w = 0;
      const double e = terms_(k.data(), points_, with_gradient ? dk.data() : nullptr, w);
      term_[t] = e;
      worst_[t] = w;
      has_gradient_[t] = with_gradient && std::isfinite(e);
      if (!std::isfinite(e)) infinite_ = true;
      if (!has_gradient_[t]) return;
      frames_.node_gradients(dk.data(), g.data(), points_);
      std::copy(g.begin(), g.end(), grad_.begin() + static_cast<std::ptrdiff_t>(t) * np_);
    });
    evaluated_ = true;
    double e = 0;
    for (int t : tets_) e += term_[t];
    if (!grad || !std::isfinite(e)) return e;
    grad->setZero(3 * num_free_);
    for (int t : tets_) {
      if (!has_gradient_[t]) continue;
      for (int i = 0; i < np_; ++i)
        if (const int f = free_[m_.tets[t * np_ + i]]; f >= 0)
          grad->segment<3>(3 * f) += grad_[static_cast<std::size_t>(t) * np_ + i];
    }
    return e;
  }

 private:
  // The least term a tet needs for a gradient: the tets below it made less
  // than gradient_share_ of E at the last evaluation (0 before the first).
  double gradient_floor() const {
    if (!evaluated_) return 0; // term_ holds the constructor's max AMIPS
    std::vector<double> terms;
    terms.reserve(tets_.size());
    double e = 0;
    for (int t : tets_) {
      terms.push_back(term_[t]);
      e += term_[t];
    }
    if (!std::isfinite(e) || gradient_share_ <= 0) return 0;
    std::sort(terms.begin(), terms.end());
    double skipped = 0;
    for (double term : terms) {
      skipped += term;
      if (skipped >= gradient_share_ * e) return term;
    }
    return 0;
  }

  static double amips(const Mat3& k) {
    const double det = k.determinant();
    return det > 0 ? k.squaredNorm() / std::cbrt(det * det) : kInf;
  }

  // fn(t, frames, scratch for dE/dK, scratch for node gradients) for every
  // tet with a free node, in parallel.
  template <class Fn>
  void for_tets(Fn fn) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tets_.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<Mat3> k(points_), dk(points_);
      std::vector<Vec3> x(np_), g(np_);
      for (std::size_t j = r.begin(); j < r.end(); ++j) {
        const int t = tets_[j];
        if (infinite_.load(std::memory_order_relaxed)) { // E is +inf whatever the rest
          term_[t] = kInf;
          continue;
        }
        for (int i = 0; i < np_; ++i) x[i] = m_.nodes[m_.tets[t * np_ + i]];
        frames_.frames(x.data(), k.data(), points_);
        fn(t, k, dk, g);
      }
    });
  }

  mesh::TetMesh& m_;
  const std::vector<int>& free_;
  int num_free_;
  double gradient_share_; // see operator()
  const highorder::AmipsFrames& frames_;
  int points_, np_;
  DescentTerms terms_;
  std::vector<int> tets_; // tets with a free node
  std::atomic<bool> infinite_{false}; // a term of the evaluation under way is +inf
  std::vector<double> term_, worst_;
  std::vector<char> has_gradient_;
  bool evaluated_ = false; // term_ holds E's terms
  std::vector<Vec3> grad_; // per tet and local node
};

// Minimizes e from the mesh's current free nodes by L-BFGS, preconditioned
// by e.inverse_curvature(); leaves the nodes at the iterate of least
// e.worst() (E's descent does not lower the worst at every step); returns
// the iterations run and sets energy to E there. Every
// o.checkpoint_iterations, that iterate, if new, is checked with
// `acceptable` (on the mesh's nodes); when the last iterate fails it, the
// nodes are left at the last that passed, so a long run is never worse
// than a check it passed on the way. Sets `passes` when the iterate left
// is one that passed (the caller need not check it again).
constexpr int kTrailSpacing = 10; // iterations between the kept earlier iterates

int lbfgs(Energy& e, const CurvedDescentOptions& o, double& energy, const std::function<bool()>& acceptable,
          bool& passes) {
  passes = false;
  Eigen::VectorXd x = e.get(), g;
  energy = e(&g);
  if (!std::isfinite(energy) || g.size() == 0) return 0;
  const Eigen::VectorXd m = e.inverse_curvature();
  Eigen::VectorXd best_x = x;
  double best_worst = e.worst(), best_energy = energy;
  int best_at = 0;
  std::deque<std::pair<Eigen::VectorXd, Eigen::VectorXd>> pairs; // (s, y)
  std::vector<double> history{energy};
  std::vector<double> best_history{best_worst}; // best_worst after each iteration
  // A least-worst iterate: where it was reached, the nodes, E and its worst.
  struct Snapshot {
    int at;
    Eigen::VectorXd x;
    double energy, worst;
  };
  std::optional<Snapshot> passed; // of the last check passed
  int checked_at = 0;             // best_at when last checked
  // Earlier least-worst iterates since the last check passed, a few
  // iterations apart: where a check fails (a tet inverted between the
  // samples), the latest of them that passes is kept instead.
  std::vector<Snapshot> trail;
  const auto check_best = [&] {
    checked_at = best_at;
    e.set(best_x);
    if (acceptable()) {
      passed = Snapshot{best_at, best_x, best_energy, best_worst};
      trail.clear();
      return;
    }
    // Bisect the trail for the latest iterate that passes (a check per step).
    std::size_t lo = 0, hi = trail.size();
    std::optional<std::size_t> found;
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      e.set(trail[mid].x);
      if (acceptable()) {
        found = mid;
        lo = mid + 1;
      } else {
        hi = mid;
      }
    }
    if (found) passed = std::move(trail[*found]);
    trail.clear();
    if (!passed) return; // nothing passed yet: the caller holds the failing tets
    // The iterate that passed is the least worst from here on, so that later
    // iterates better than it (not only than the one that failed) count, and
    // the stop rules see no gain since it.
    best_x = passed->x;
    best_energy = passed->energy;
    best_worst = passed->worst;
    best_at = checked_at = passed->at;
    for (std::size_t i = passed->at + 1; i < best_history.size(); ++i) best_history[i] = best_worst;
  };
  int it = 0;
  for (; it < o.max_iterations; ++it) {
    // Two-loop recursion: d = -H g, H0 = gamma diag(m).
    Eigen::VectorXd d = -g;
    std::vector<double> alpha(pairs.size());
    for (int k = static_cast<int>(pairs.size()) - 1; k >= 0; --k) {
      alpha[k] = pairs[k].first.dot(d) / pairs[k].second.dot(pairs[k].first);
      d -= alpha[k] * pairs[k].second;
    }
    d = d.cwiseProduct(m);
    if (!pairs.empty()) {
      const auto& [s, y] = pairs.back();
      d *= s.dot(y) / y.cwiseProduct(m).dot(y);
    } else { // first step: a thousandth of the model's size over the nodes
      d *= 1e-3 * std::sqrt(static_cast<double>(x.size())) / std::max(d.norm(), 1e-300) * x.cwiseAbs().maxCoeff();
    }
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const double beta = pairs[k].second.dot(d) / pairs[k].second.dot(pairs[k].first);
      d += (alpha[k] - beta) * pairs[k].first;
    }
    const double slope = g.dot(d);
    Eigen::VectorXd xn, gn;
    double en = kInf, step = 1;
    for (int halvings = 0; halvings < 40 && slope < 0; ++halvings, step *= 0.5) {
      xn = x + step * d;
      e.set(xn);
      en = e(&gn);
      if (en <= energy + 1e-4 * step * slope) break;
    }
    if (!(en < energy)) {
      if (!e.partial_gradients()) break;
      // The tets left out of the gradient mattered here: every tet's
      // gradient from now on, and L-BFGS afresh.
      e.use_every_gradient();
      e.set(x);
      energy = e(&g);
      pairs.clear();
      continue;
    }
    const Eigen::VectorXd s = xn - x, y = gn - g;
    if (s.dot(y) > 0) {
      pairs.emplace_back(s, y);
      if (static_cast<int>(pairs.size()) > o.memory) pairs.pop_front();
    }
    x = std::move(xn);
    g = std::move(gn);
    energy = en;
    if (const double w = e.worst(); w <= best_worst) { // E falls: the later of equals
      if (w < best_worst) best_at = it + 1;
      best_worst = w;
      best_x = x;
      best_energy = energy;
      if (trail.empty() || best_at >= trail.back().at + kTrailSpacing) trail.push_back({best_at, x, energy, w});
    }
    history.push_back(energy);
    if ((it + 1) % o.checkpoint_iterations == 0) {
      logger().debug("curved descent: iteration {}, E {:.4g}, least worst {:.4g} (at {})", it + 1, energy, best_worst,
                     best_at);
      if (best_at > checked_at) {
        check_best();
        e.set(x);
      }
    }
    best_history.push_back(best_worst);
    const int n = static_cast<int>(history.size());
    const bool e_stalled = n > o.window && history[n - 1 - o.window] - energy < o.min_decrease * history[n - 1 - o.window];
    const auto stalled_over = [&](int w) {
      return best_history[n - 1 - w] - best_worst < o.min_worst_decrease * best_history[n - 1 - w];
    };
    const bool worst_stalled = (n > o.worst_window && stalled_over(o.worst_window)) ||
                               (n == o.first_window + 1 && stalled_over(o.first_window));
    if (e_stalled || worst_stalled) {
      ++it;
      break;
    }
  }
  if (passed && best_at > checked_at) check_best();
  if (passed) {
    passes = true;
    // A later iterate of equal worst replaces best_x without a new best_at,
    // so it was never checked: back to the one that passed.
    if (passed->x != best_x) {
      best_x = passed->x;
      best_energy = passed->energy;
    }
  }
  e.set(best_x);
  energy = best_energy;
  return it;
}

} // namespace

nlohmann::json CurvedDescentStats::json() const {
  return {{"free_nodes", free_nodes},   {"iterations", iterations},     {"held_tets", held_tets}, {"restored_tets", restored_tets},
          {"energy_before", energy_before}, {"energy_after", energy_after}, {"seconds", seconds}};
}

CurvedDescentStats descend_curved(mesh::TetMesh& m, const CurvedDescentOptions& o,
                                  std::vector<highorder::TetQuality>* quality_io) {
  const auto start = std::chrono::steady_clock::now();
  CurvedDescentStats s;
  const int nt = m.num_tets(), np = m.tet_nodes();
  if (nt == 0) return s;
  const auto quality = [&](int t) {
    std::vector<Vec3> x(np);
    for (int i = 0; i < np; ++i) x[i] = m.nodes[m.tets[t * np + i]];
    return std::pair{highorder::tet_quality(m.order, x.data()), std::move(x)};
  };
  // The input's worst: the acceptance's bounds.
  std::vector<highorder::TetQuality> before;
  if (quality_io && static_cast<int>(quality_io->size()) == nt) {
    before = std::move(*quality_io);
  } else {
    before.resize(nt);
    tbb::parallel_for(0, nt, [&](int t) { before[t] = quality(t).first; });
  }
  double max_amips = 0, min_sj = kInf;
  for (const auto& q : before) {
    max_amips = std::max(max_amips, q.max_amips);
    min_sj = std::min(min_sj, q.min_scaled_jacobian);
  }
  const double sj_floor = std::min(min_sj, o.min_scaled_jacobian);
  const auto failing = [&](const std::vector<int>& tets) {
    std::vector<char> fails(tets.size(), 0);
    tbb::parallel_for(std::size_t(0), tets.size(), [&](std::size_t k) {
      const auto [q, x] = quality(tets[k]);
      fails[k] = !(q.max_amips <= max_amips) || !(q.min_scaled_jacobian >= sj_floor) ||
                 highorder::certify_tet(m.order, x.data()).validity != highorder::Validity::positive;
    });
    std::vector<int> out;
    for (std::size_t k = 0; k < tets.size(); ++k)
      if (fails[k]) out.push_back(tets[k]);
    return out;
  };

  std::vector<std::vector<int>> tets_of(m.nodes.size());
  for (int t = 0; t < nt; ++t)
    for (int i = 0; i < np; ++i) tets_of[m.tets[t * np + i]].push_back(t);

  const std::vector<Vec3> original = m.nodes;
  std::vector<char> held = pinned_nodes(m); // nodes that stay where they are
  // Only the worst tets and `rings` layers of tets around them move: the
  // others weigh (active_ratio)^p or less in E.
  std::vector<char> active(nt, 0);
  for (int t = 0; t < nt; ++t)
    active[t] = before[t].max_amips >= o.active_ratio * max_amips || before[t].min_scaled_jacobian * o.active_ratio <= min_sj;
  for (int ring = 0; ring < o.rings; ++ring) {
    std::vector<char> grown = active;
    for (int t = 0; t < nt; ++t)
      if (active[t])
        for (int i = 0; i < np; ++i)
          for (int u : tets_of[m.tets[t * np + i]]) grown[u] = 1;
    active = std::move(grown);
  }
  {
    std::vector<char> moves(m.nodes.size(), 0);
    for (int t = 0; t < nt; ++t)
      if (active[t])
        for (int i = 0; i < np; ++i) moves[m.tets[t * np + i]] = 1;
    for (std::size_t n = 0; n < held.size(); ++n) held[n] = held[n] || !moves[n];
  }
  std::vector<int> touched;                 // tets with a free node
  for (int round = 0; round < kRounds; ++round) {
    std::vector<int> free_index(m.nodes.size(), -1);
    int free_nodes = 0;
    touched.clear();
    for (int t = 0; t < nt; ++t) {
      bool any = false;
      for (int i = 0; i < np; ++i)
        if (const int n = m.tets[t * np + i]; !held[n]) {
          any = true;
          if (free_index[n] < 0) free_index[n] = free_nodes++;
        }
      if (any) touched.push_back(t);
    }
    if (round == 0) s.free_nodes = free_nodes;
    if (free_nodes == 0) break;
    std::optional<Energy> energy(std::in_place, m, free_index, free_nodes, o.power, o.gradient_share);
    if (round == 0) s.energy_before = (*energy)(nullptr) / energy->points();
    // Held nodes put back can invert a tet sharing them: then all start
    // again from the input.
    if (round > 0 && !std::isfinite((*energy)(nullptr))) {
      m.nodes = original;
      energy.emplace(m, free_index, free_nodes, o.power, o.gradient_share);
    }
    double e = 0;
    bool passes = false;
    s.iterations += lbfgs(*energy, o, e, [&] { return failing(touched).empty(); }, passes);
    s.energy_after = e / energy->points();
    // A tet that fails the acceptance gets its nodes back and keeps them;
    // the others go on from where they are.
    const std::vector<int> bad = passes ? std::vector<int>{} : failing(touched);
    if (bad.empty()) {
      touched.clear();
      break;
    }
    if (round + 1 == kRounds) break;
    for (int t : bad) {
      ++s.held_tets;
      for (int i = 0; i < np; ++i) {
        const int n = m.tets[t * np + i];
        held[n] = 1;
        m.nodes[n] = original[n];
      }
    }
  }
  // Still failing after the last round: restore tets one by one, checking
  // their neighbours again (restoring every node gives the input back).
  for (std::vector<int> bad = failing(touched); !bad.empty();) {
    std::vector<int> next;
    for (int t : bad)
      for (int i = 0; i < np; ++i) {
        const int n = m.tets[t * np + i];
        if (m.nodes[n] == original[n]) continue;
        m.nodes[n] = original[n];
        next.insert(next.end(), tets_of[n].begin(), tets_of[n].end());
      }
    s.restored_tets += static_cast<int>(bad.size());
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    bad = failing(next);
  }
  if (quality_io) {
    // Only tets with a moved node changed.
    std::vector<int> moved;
    for (int t = 0; t < nt; ++t)
      for (int i = 0; i < np; ++i)
        if (const int n = m.tets[t * np + i]; m.nodes[n] != original[n]) {
          moved.push_back(t);
          break;
        }
    tbb::parallel_for(std::size_t(0), moved.size(), [&](std::size_t k) { before[moved[k]] = quality(moved[k]).first; });
    *quality_io = std::move(before);
  }
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  logger().debug("curved descent: {} free nodes, {} iterations, E {:.4g} -> {:.4g}, {} tets held, {} restored, {:.2f} s",
                 s.free_nodes, s.iterations, s.energy_before, s.energy_after, s.held_tets, s.restored_tets, s.seconds);
  return s;
}

} // namespace curvetet::volume

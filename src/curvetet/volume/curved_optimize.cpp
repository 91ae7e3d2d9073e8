#include "curvetet/volume/curved_optimize.hpp"

#include "curvetet/highorder/amips_frames.hpp"
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quality.hpp"

#include <tbb/parallel_for.h>

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
  std::vector<std::pair<int, double>> nodes;
  std::vector<int> tets;
};

class CurvedOptimizer {
 public:
  CurvedOptimizer(mesh::TetMesh& m, const CurvedOptimizeOptions& o)
      : m_(m), o_(o), np_(m.tet_nodes()), table_(highorder::amips_frames(m.order)), q_(table_.num_points()) {
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
    weight_.assign(n, 0);
    amips_.assign(m.num_tets(), 0);
    frames_.resize(static_cast<std::size_t>(m.num_tets()) * q_);
    tbb::parallel_for(0, m_.num_tets(), [&](int t) { refresh(t); });
  }

  const std::vector<double>& amips() const { return amips_; }

  // One sweep over the tets at or above the threshold, worst first.
  void sweep(double threshold, CurvedOptimizeStats& stats) {
    std::vector<int> bad;
    for (int t = 0; t < m_.num_tets(); ++t)
      if (amips_[t] >= threshold) bad.push_back(t);
    std::stable_sort(bad.begin(), bad.end(), [&](int a, int b) { return amips_[a] > amips_[b]; });
    std::vector<char> tried(m_.nodes.size(), 0);
    for (int t : bad) {
      if (amips_[t] < threshold) continue; // improved by an earlier move
      for (int i = 0; i < np_; ++i) {
        const int id = m_.tet(t)[i];
        if (frozen_[id] || tried[id]) continue;
        const bool is_corner = i < 4;
        if (is_corner ? !o_.move_vertices : !o_.move_nodes) continue;
        tried[id] = 1;
        const Move mv = is_corner ? vertex_move(id) : node_move(id);
        if (mv.nodes.empty()) continue;
        // Moving one high-order node of a straight tet changes its Jacobian
        // by d (x) grad(phi_node), whose sign varies over the tet, so its true
        // max AMIPS rises (a dip of the max sampled at quadrature points is
        // an artefact): only try when the worst touched tet is curved.
        if (!is_corner && straight(worst_of(mv.tets))) continue;
        if (try_move(mv, stats)) ++(is_corner ? stats.vertex_moves : stats.node_moves);
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

  // Frames and max AMIPS of tet t from its nodes.
  void refresh(int t) {
    Vec3 nodes[165]; // order <= 8
    for (int i = 0; i < np_; ++i) nodes[i] = m_.nodes[m_.tet(t)[i]];
    Eigen::Matrix3d* k = &frames_[static_cast<std::size_t>(t) * q_];
    table_.frames(nodes, k);
    amips_[t] = table_.max_amips(k, nullptr, Vec3::Zero());
  }

  bool certified(int t) const {
    Vec3 nodes[165];
    for (int i = 0; i < np_; ++i) nodes[i] = m_.nodes[m_.tet(t)[i]];
    return highorder::certify_tet(m_.order, nodes).validity == highorder::Validity::positive;
  }

  // Corner v and the star's nodes weighted by their barycentric weight on v.
  // Empty when a node with a non-zero weight is frozen.
  Move vertex_move(int v) const {
    Move mv;
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
    mv.nodes.emplace_back(id, 1.0);
    for (int k = offset_[id]; k < offset_[id + 1]; ++k) mv.tets.push_back(uses_[k].first);
    std::sort(mv.tets.begin(), mv.tets.end());
    mv.tets.erase(std::unique(mv.tets.begin(), mv.tets.end()), mv.tets.end());
    return mv;
  }

  // Rank-one directions of the move in every touched tet (AmipsFrames):
  // directions_[k * q_ + q] for tet mv.tets[k].
  void set_directions(const Move& mv) {
    directions_.assign(mv.tets.size() * q_, Vec3::Zero());
    for (const auto& [id, w] : mv.nodes) weight_[id] = w;
    for (std::size_t k = 0; k < mv.tets.size(); ++k)
      for (int i = 0; i < np_; ++i)
        if (const double w = weight_[m_.tet(mv.tets[k])[i]]; w != 0) table_.add_direction(i, w, &directions_[k * q_]);
    for (const auto& [id, w] : mv.nodes) weight_[id] = 0;
  }

  // Max AMIPS of the touched tets mv.tets[k], k in `which`, were the move's
  // nodes displaced by d; stops early (returning a value >= bound) once a
  // tet reaches `bound`.
  double trial(const Move& mv, const std::vector<int>& which, const Vec3& d,
               double bound = std::numeric_limits<double>::infinity()) const {
    double worst = 0;
    for (int k : which) {
      const auto t = static_cast<std::size_t>(mv.tets[k]);
      worst = std::max(worst, table_.max_amips(&frames_[t * q_], &directions_[k * q_], d, bound));
      if (worst >= bound) break;
    }
    return worst;
  }

  void place(const Move& mv, const std::vector<Vec3>& saved, const Vec3& d) {
    for (std::size_t k = 0; k < mv.nodes.size(); ++k) m_.nodes[mv.nodes[k].first] = saved[k] + mv.nodes[k].second * d;
  }

  // Shortest corner edge of the touched tets: the scale of the steps.
  double edge_scale(const Move& mv) const {
    double h = std::numeric_limits<double>::infinity();
    for (int t : mv.tets)
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) h = std::min(h, (m_.nodes[m_.tet(t)[a]] - m_.nodes[m_.tet(t)[b]]).norm());
    return h;
  }

  bool try_move(const Move& mv, CurvedOptimizeStats& stats) {
    double f0 = 0;
    for (int t : mv.tets) f0 = std::max(f0, amips_[t]);
    const double h = edge_scale(mv);
    if (!(h > 0) || !std::isfinite(f0)) return false;
    set_directions(mv);

    // Touched tets worst first; the ones near the max decide the direction.
    std::vector<int> order(mv.tets.size()), active;
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return amips_[mv.tets[a]] > amips_[mv.tets[b]]; });
    for (int k : order)
      if (amips_[mv.tets[k]] >= 0.5 * f0) active.push_back(k);

    // Descent direction of the max AMIPS, central differences.
    const double fd = 1e-5 * h;
    Vec3 g = Vec3::Zero();
    for (int a = 0; a < 3; ++a) {
      const Vec3 e = fd * Vec3::Unit(a);
      const double plus = trial(mv, active, e), minus = trial(mv, active, -e);
      if (std::isfinite(plus) && std::isfinite(minus)) g[a] = (plus - minus) / (2 * fd);
    }
    if (!(g.norm() > 0)) {
      ++stats.rejected_quality;
      return false;
    }
    const Vec3 dir = -g.normalized();

    std::vector<Vec3> saved;
    for (const auto& [id, w] : mv.nodes) saved.push_back(m_.nodes[id]);
    bool certificate_failed = false;
    double step = 0.25 * h;
    for (int s = 0; s < o_.line_search_steps; ++s, step *= 0.5) {
      const double bound = f0 * (1 - 1e-6);
      if (!(trial(mv, order, step * dir, bound) < bound)) continue;
      place(mv, saved, step * dir);
      bool ok = true;
      for (int t : mv.tets) ok = ok && certified(t);
      if (ok) {
        for (int t : mv.tets) refresh(t);
        return true;
      }
      certificate_failed = true;
      place(mv, saved, Vec3::Zero()); // saved + 0 * d: bit-exact restore
    }
    ++(certificate_failed ? stats.rejected_certificate : stats.rejected_quality);
    return false;
  }

  mesh::TetMesh& m_;
  const CurvedOptimizeOptions& o_;
  const int np_;
  std::vector<char> frozen_; // nodes of listed boundary triangles
  std::vector<int> offset_;
  std::vector<std::pair<int, int>> uses_;
  std::vector<std::array<double, 4>> barycentric_; // of each local node
  const highorder::AmipsFrames& table_;
  const int q_; // quadrature points per tet
  std::vector<Eigen::Matrix3d> frames_; // q_ per tet
  std::vector<double> amips_;           // max AMIPS per tet, from its frames
  std::vector<double> weight_;          // scratch: weight of each node in the current move
  std::vector<Vec3> directions_;        // the current move's rank-one directions
};

struct Summary {
  double max_amips = 0, mean_amips = 0, min_scaled_jacobian = 0;
};

Summary summarize(const mesh::TetMesh& m) {
  const int n = m.num_tets();
  std::vector<highorder::TetQuality> q(n);
  tbb::parallel_for(0, n, [&](int t) {
    std::vector<Vec3> nodes(m.tet_nodes());
    for (int i = 0; i < m.tet_nodes(); ++i) nodes[i] = m.nodes[m.tet(t)[i]];
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

} // namespace

CurvedOptimizeStats optimize_curved(mesh::TetMesh& m, const CurvedOptimizeOptions& o) {
  CurvedOptimizeStats stats;
  const Summary before = summarize(m);
  stats.max_amips_before = before.max_amips;
  stats.mean_amips_before = before.mean_amips;
  stats.min_scaled_jacobian_before = before.min_scaled_jacobian;
  if (m.num_tets() > 0) {
    CurvedOptimizer opt(m, o);
    for (int pass = 0; pass < o.passes; ++pass) {
      std::vector<double> sorted = opt.amips();
      const std::size_t k = std::min(sorted.size() - 1, static_cast<std::size_t>(o.bad_fraction * sorted.size()));
      std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end(), std::greater<>());
      const double threshold = std::max(o.min_amips, sorted[k]);
      const int moves = stats.vertex_moves + stats.node_moves;
      opt.sweep(threshold, stats);
      ++stats.passes;
      if (stats.vertex_moves + stats.node_moves == moves) break;
    }
  }
  const Summary after = summarize(m);
  stats.max_amips_after = after.max_amips;
  stats.mean_amips_after = after.mean_amips;
  stats.min_scaled_jacobian_after = after.min_scaled_jacobian;
  return stats;
}

} // namespace curvetet::volume

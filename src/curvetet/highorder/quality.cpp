#include "curvetet/highorder/quality.hpp"

#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quadrature.hpp"

#include <Eigen/Dense>

#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/simplex_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace curvetet::highorder {

namespace {

const Eigen::Matrix3d& regular_tet_inverse() {
  static const Eigen::Matrix3d inv = [] {
    Eigen::Matrix3d w;
    w.col(0) << 1, 0, 0;
    w.col(1) << 0.5, std::sqrt(3.0) / 2, 0;
    w.col(2) << 0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0);
    return Eigen::Matrix3d(w.inverse());
  }();
  return inv;
}

// Per order: the sample points of the convention (quality.hpp), the
// Lagrange gradients there, and the nodes' reference coordinates (for the
// straight-tet test).
struct TetSamples {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::MatrixXd> gradients; // N x 3 each
  std::vector<Eigen::Vector3d> node_xi;
};

const TetSamples& tet_samples(int order) {
  if (order < 1 || order > kMaxOrder) throw std::invalid_argument("tet_quality: order must be 1..8");
  static std::unique_ptr<TetSamples> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] {
    auto s = std::make_unique<TetSamples>();
    if (order == 1) {
      s->points.emplace_back(0.25, 0.25, 0.25);
    } else {
      // The order-2P lattice, then the points of the degree-3(P-1) lattice
      // not on it (alpha / m == beta / n exactly when n alpha == m beta).
      const int m = 2 * order, n = 3 * (order - 1);
      const SimplexLattice& a = lattice(3, m);
      for (int i = 0; i < a.size(); ++i) s->points.emplace_back(a[i][1] / double(m), a[i][2] / double(m), a[i][3] / double(m));
      const SimplexLattice& b = lattice(3, n);
      for (int i = 0; i < b.size(); ++i) {
        const bool on_a = (b[i][1] * m) % n == 0 && (b[i][2] * m) % n == 0 && (b[i][3] * m) % n == 0;
        if (!on_a) s->points.emplace_back(b[i][1] / double(n), b[i][2] / double(n), b[i][3] / double(n));
      }
    }
    for (const auto& xi : s->points) s->gradients.push_back(lagrange_gradients(3, order, xi.data()));
    for (int i = 0; i < tet_node_count(order); ++i) {
      const auto p = tet_node(order, i);
      s->node_xi.emplace_back(double(p[0]) / order, double(p[1]) / order, double(p[2]) / order);
    }
    // The straight test below takes the corners as nodes 0..3 at the
    // reference tet's corners (Gmsh's order).
    const Eigen::Vector3d corners[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int v = 0; v < 4; ++v)
      if (s->node_xi[v] != corners[v]) throw std::logic_error("tet_quality: unexpected corner order");
    cache[order] = std::move(s);
  });
  return *cache[order];
}

// Whether every node sits where the affine map of the corners puts it (to
// 1e-12 of the tet's size: the test of curved_optimize.cpp's straight());
// then the Jacobian is the constant edge matrix `e`.
bool straight(const TetSamples& s, const Eigen::Vector3d* nodes, Eigen::Matrix3d& e) {
  e << nodes[1] - nodes[0], nodes[2] - nodes[0], nodes[3] - nodes[0];
  const double scale = e.cwiseAbs().maxCoeff();
  for (std::size_t i = 4; i < s.node_xi.size(); ++i)
    if ((nodes[i] - nodes[0] - e * s.node_xi[i]).cwiseAbs().maxCoeff() > 1e-12 * scale) return false;
  return true;
}

} // namespace

double scaled_jacobian(const Eigen::Matrix3d& j) {
  const double det = j.determinant();
  const Eigen::Vector3d a = j.col(0), b = j.col(1), c = j.col(2);
  // Squared lengths of the six edge derivatives; each corner of the
  // reference tet uses the three edges leaving it.
  const double aa = a.squaredNorm(), bb = b.squaredNorm(), cc = c.squaredNorm();
  const double ab = (b - a).squaredNorm(), ac = (c - a).squaredNorm(), bc = (c - b).squaredNorm();
  const double frames[4] = {aa * bb * cc, aa * ab * ac, bb * ab * bc, cc * ac * bc};
  // det / sqrt(f) is monotone in f, so one square root decides the min over
  // the corners: at the largest f when det > 0, else at the smallest
  // positive one; a degenerate frame (f = 0) counts as +-1.
  double largest = 0, smallest_positive = 0;
  bool degenerate = false;
  for (double f : frames) {
    if (!(f > 0)) {
      degenerate = true;
      continue;
    }
    largest = std::max(largest, f);
    smallest_positive = smallest_positive > 0 ? std::min(smallest_positive, f) : f;
  }
  double best = degenerate ? (det > 0 ? 1.0 : -1.0) : std::numeric_limits<double>::infinity();
  const double f = det > 0 ? largest : smallest_positive;
  if (f > 0) best = std::min(best, std::sqrt(2.0) * det / std::sqrt(f));
  return best;
}

double amips(const Eigen::Matrix3d& j) {
  const Eigen::Matrix3d jr = j * regular_tet_inverse();
  const double det = jr.determinant();
  if (!(det > 0)) return std::numeric_limits<double>::infinity();
  return jr.squaredNorm() / std::cbrt(det * det);
}

double triangle_mips(const Eigen::Matrix<double, 3, 2>& j) {
  Eigen::Matrix2d w;
  w << 1, 0.5, 0, std::sqrt(3.0) / 2;
  const Eigen::Matrix<double, 3, 2> jr = j * w.inverse();
  const Eigen::Matrix2d g = jr.transpose() * jr;
  const double det = g.determinant();
  if (!(det > 0)) return std::numeric_limits<double>::infinity();
  return g.trace() / (2.0 * std::sqrt(det));
}

const std::vector<Eigen::Vector3d>& quality_samples(int order) { return tet_samples(order).points; }

int quality_lattice_points(int order) {
  if (order == 1) return 1;
  const int m = 2 * order;
  return (m + 1) * (m + 2) * (m + 3) / 6;
}

TetQuality tet_quality(int order, const Eigen::Vector3d* nodes) {
  const TetSamples& samples = tet_samples(order);
  TetQuality q;
  Eigen::Matrix3d e;
  if (straight(samples, nodes, e)) {
    q.min_scaled_jacobian = scaled_jacobian(e);
    q.max_amips = q.mean_amips = amips(e);
    return q;
  }
  const int n = tet_node_count(order);
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> x(nodes[0].data(), 3, n);
  q.min_scaled_jacobian = std::numeric_limits<double>::infinity();
  double sum = 0;
  for (const auto& g : samples.gradients) {
    const Eigen::Matrix3d j = x.lazyProduct(g);
    q.min_scaled_jacobian = std::min(q.min_scaled_jacobian, scaled_jacobian(j));
    const double a = amips(j);
    q.max_amips = std::max(q.max_amips, a);
    sum += a;
  }
  q.mean_amips = sum / static_cast<double>(samples.gradients.size());
  return q;
}

namespace {

// Per order: the Lagrange gradients at the points of the order-2P lattice
// (triangle_max_mips runs on every patch the coarsening fits).
const std::vector<Eigen::MatrixXd>& triangle_lattice_gradients(int order) {
  if (order < 2 || order > kMaxOrder) throw std::invalid_argument("triangle_max_mips: lattice gradients for order 2..8 only");
  static std::vector<Eigen::MatrixXd> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] {
    for (const MultiIndex& a : lattice(2, 2 * order).indices()) {
      const Eigen::Vector2d uv(a[1] / double(2 * order), a[2] / double(2 * order));
      cache[order].push_back(lagrange_gradients(2, order, uv.data()));
    }
  });
  return cache[order];
}

} // namespace

double triangle_max_mips(int order, const Eigen::Vector3d* nodes) {
  if (order == 1) return triangle_mips(triangle_jacobian(1, nodes, Eigen::Vector2d::Zero()));
  double m = 0;
  for (const Eigen::MatrixXd& g : triangle_lattice_gradients(order)) {
    m = std::max(m, triangle_mips(triangle_jacobian(g, nodes)));
    if (!std::isfinite(m)) break;
  }
  return m;
}

} // namespace curvetet::highorder

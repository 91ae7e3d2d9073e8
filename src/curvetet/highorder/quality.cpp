#include "curvetet/highorder/quality.hpp"

#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quadrature.hpp"

#include <Eigen/Dense>

#include "curvetet/highorder/bernstein.hpp"

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

// Lagrange gradients at the sample points of tet_quality, once per order:
// first the nodes (scaled Jacobian only), then the quadrature points.
struct TetSamples {
  std::vector<Eigen::MatrixXd> gradients; // N x 3 each
  std::size_t num_nodes = 0;
  std::vector<double> weights; // quadrature points only
};

const TetSamples& tet_samples(int order) {
  static std::unique_ptr<TetSamples> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] {
    auto s = std::make_unique<TetSamples>();
    for (int i = 0; i < tet_node_count(order); ++i) {
      auto p = tet_node(order, i);
      const double xi[3] = {double(p[0]) / order, double(p[1]) / order, double(p[2]) / order};
      s->gradients.push_back(lagrange_gradients(3, order, xi));
    }
    s->num_nodes = s->gradients.size();
    const Quadrature rule = tet_quadrature(order + 1);
    for (std::size_t k = 0; k < rule.points.size(); ++k) {
      s->gradients.push_back(lagrange_gradients(3, order, rule.points[k].data()));
      s->weights.push_back(rule.weights[k]);
    }
    cache[order] = std::move(s);
  });
  return *cache[order];
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
  double best = std::numeric_limits<double>::infinity();
  for (double f : frames) {
    const double s = f > 0 ? std::sqrt(2.0) * det / std::sqrt(f) : (det > 0 ? 1.0 : -1.0);
    best = std::min(best, s);
  }
  return best;
}

double amips(const Eigen::Matrix3d& j) {
  const Eigen::Matrix3d jr = j * regular_tet_inverse();
  const double det = jr.determinant();
  if (!(det > 0)) return std::numeric_limits<double>::infinity();
  return jr.squaredNorm() / (3.0 * std::cbrt(det * det));
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

TetQuality tet_quality(int order, const Eigen::Vector3d* nodes) {
  if (order < 1 || order > kMaxOrder) throw std::invalid_argument("tet_quality: order must be 1..8");
  const TetSamples& samples = tet_samples(order);
  const int n = tet_node_count(order);
  Eigen::Matrix<double, 3, Eigen::Dynamic> x(3, n);
  for (int i = 0; i < n; ++i) x.col(i) = nodes[i];
  TetQuality q;
  q.min_scaled_jacobian = std::numeric_limits<double>::infinity();
  double sum = 0, wsum = 0;
  for (std::size_t k = 0; k < samples.gradients.size(); ++k) {
    const Eigen::Matrix3d j = x.lazyProduct(samples.gradients[k]);
    q.min_scaled_jacobian = std::min(q.min_scaled_jacobian, scaled_jacobian(j));
    if (k < samples.num_nodes) continue;
    const double w = samples.weights[k - samples.num_nodes];
    const double e = amips(j);
    q.max_amips = std::max(q.max_amips, e);
    sum += w * e;
    wsum += w;
  }
  q.mean_amips = sum / wsum;
  return q;
}

double triangle_max_mips(int order, const Eigen::Vector3d* nodes) {
  const Quadrature rule = triangle_quadrature(order + 1);
  double m = 0;
  for (const auto& p : rule.points) m = std::max(m, triangle_mips(triangle_jacobian(order, nodes, p.head<2>())));
  return m;
}

} // namespace curvetet::highorder

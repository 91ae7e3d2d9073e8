#include "curvetet/highorder/amips_frames.hpp"

#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quality.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace curvetet::highorder {

AmipsFrames::AmipsFrames(int order) {
  if (order < 1 || order > kMaxOrder) throw std::invalid_argument("AmipsFrames: order must be 1..8");
  // W: reference tet -> regular tet of unit edge (columns = its edge vectors).
  w_.col(0) << 1, 0, 0;
  w_.col(1) << 0.5, std::sqrt(3.0) / 2, 0;
  w_.col(2) << 0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0);
  const Eigen::Matrix3d w_inv = w_.inverse();
  const Eigen::Vector3d e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY(), e3 = Eigen::Vector3d::UnitZ();
  const CornerEdges reference = {{{e1, e2, e3}, {e1, e2 - e1, e3 - e1}, {e2, e2 - e1, e3 - e2}, {e3, e3 - e1, e3 - e2}}};
  for (int c = 0; c < 4; ++c)
    for (int i = 0; i < 3; ++i) corner_edges_[c][i] = w_ * reference[c][i];
  nodes_ = tet_node_count(order);
  const std::vector<Eigen::Vector3d>& xis = quality_samples(order);
  points_ = static_cast<int>(xis.size());
  lattice_points_ = quality_lattice_points(order);
  h_.resize(nodes_, 3 * points_);
  for (int q = 0; q < points_; ++q) h_.middleCols<3>(3 * q) = lagrange_gradients(3, order, xis[q].data()) * w_inv;
}

void AmipsFrames::frames(const Eigen::Vector3d* nodes, Eigen::Matrix3d* frames, int points) const {
  // All frames at once: [K_0 K_1 ...] = X H, X = [x_0 ... x_n-1] (3 x n);
  // an array of column-major Matrix3d is that 3 x 3P column-major matrix.
  const int n = points < 0 ? points_ : std::min(points, points_);
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> x(nodes[0].data(), 3, nodes_);
  Eigen::Map<Eigen::Matrix<double, 3, Eigen::Dynamic>> k(frames[0].data(), 3, 3 * n);
  k.noalias() = x * h_.leftCols(3 * n);
}

void AmipsFrames::node_gradients(const Eigen::Matrix3d* dfdk, Eigen::Vector3d* out, int points) const {
  const int n = points < 0 ? points_ : std::min(points, points_);
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> g(dfdk[0].data(), 3, 3 * n);
  Eigen::Map<Eigen::Matrix<double, 3, Eigen::Dynamic>> x(out[0].data(), 3, nodes_);
  x.noalias() = g * h_.leftCols(3 * n).transpose();
}

void AmipsFrames::add_direction(int local, double w, Eigen::Vector3d* c) const {
  for (int q = 0; q < points_; ++q) c[q] += w * h_.row(local).segment<3>(3 * q).transpose();
}

double AmipsFrames::max_amips(const Eigen::Matrix3d* frames, const Eigen::Vector3d* c, const Eigen::Vector3d& d,
                              double bound, int points, int from) const {
  const int n = points < 0 ? points_ : std::min(points, points_);
  const double bound_cubed = bound * bound * bound;
  double worst_cubed = 0;
  for (int q = from; q < n && worst_cubed < bound_cubed; ++q) {
    Eigen::Matrix3d k = frames[q];
    if (c) k.noalias() += d * c[q].transpose();
    const double det = k.determinant();
    if (!(det > 0)) return std::numeric_limits<double>::infinity();
    const double n2 = k.squaredNorm();
    worst_cubed = std::max(worst_cubed, n2 * n2 * n2 / (det * det));
  }
  return std::cbrt(worst_cubed);
}

double AmipsFrames::min_scaled_jacobian(const Eigen::Matrix3d* frames, const Eigen::Vector3d* c,
                                        const Eigen::Vector3d& d, double floor, int points, int from) const {
  const int n = points < 0 ? points_ : std::min(points, points_);
  double worst = std::numeric_limits<double>::infinity();
  for (int q = from; q < n && !(worst < floor); ++q) {
    Eigen::Matrix3d k = frames[q];
    if (c) k.noalias() += d * c[q].transpose();
    worst = std::min(worst, scaled_jacobian(k * w_));
  }
  return worst;
}

int AmipsFrames::worst_amips_point(const Eigen::Matrix3d* frames, int points, double* value) const {
  const int n = points < 0 ? points_ : std::min(points, points_);
  int worst = -1;
  *value = -std::numeric_limits<double>::infinity();
  for (int q = 0; q < n; ++q) {
    const double a = max_amips(frames + q, nullptr, Eigen::Vector3d::Zero(), std::numeric_limits<double>::infinity(), 1);
    if (a > *value) {
      *value = a;
      worst = q;
    }
  }
  return worst;
}

int AmipsFrames::worst_scaled_jacobian_point(const Eigen::Matrix3d* frames, int points, double* value) const {
  const int n = points < 0 ? points_ : std::min(points, points_);
  int worst = -1;
  *value = std::numeric_limits<double>::infinity();
  for (int q = 0; q < n; ++q) {
    const double sj = scaled_jacobian(frames[q] * w_);
    if (sj < *value) {
      *value = sj;
      worst = q;
    }
  }
  return worst;
}

Eigen::Vector3d AmipsFrames::amips_gradient(const Eigen::Matrix3d& k, const Eigen::Vector3d& c) const {
  // AMIPS = |K|^2 det^(-2/3): dA/dK = (2 K - (2/3) |K|^2 K^-T) det^(-2/3).
  const double det = k.determinant(), norm2 = k.squaredNorm();
  const Eigen::Matrix3d dk = (2 * k - (2.0 / 3.0) * norm2 * k.inverse().transpose()) / std::cbrt(det * det);
  return dk * c;
}

Eigen::Vector3d AmipsFrames::scaled_jacobian_gradient(const Eigen::Matrix3d& k, const Eigen::Vector3d& c) const {
  // The corner frame that decides (quality.cpp's scaled_jacobian: the
  // largest product of squared edge lengths), with u its reference edges
  // (corner_edges() holds W u):
  // d log sJ / dK = K^-T - sum_u (K W u)(W u)^T / |K W u|^2.
  const Eigen::Matrix3d j = k * w_;
  double largest = -1;
  int corner = 0;
  for (int i = 0; i < 4; ++i) {
    double f = 1;
    for (const auto& wu : corner_edges_[i]) f *= (k * wu).squaredNorm();
    if (f > largest) {
      largest = f;
      corner = i;
    }
  }
  Eigen::Matrix3d dlog = k.inverse().transpose();
  for (const auto& wu : corner_edges_[corner]) {
    const Eigen::Vector3d kwu = k * wu;
    dlog -= kwu * wu.transpose() / kwu.squaredNorm();
  }
  return scaled_jacobian(j) * (dlog * c);
}

const AmipsFrames& amips_frames(int order) {
  if (order < 1 || order > kMaxOrder) throw std::invalid_argument("amips_frames: order must be 1..8");
  static std::unique_ptr<AmipsFrames> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] { cache[order] = std::make_unique<AmipsFrames>(order); });
  return *cache[order];
}

} // namespace curvetet::highorder

#include "curvetet/highorder/amips_frames.hpp"

#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quality.hpp"

#include <Eigen/Dense>

#include <algorithm>
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

const AmipsFrames& amips_frames(int order) {
  if (order < 1 || order > kMaxOrder) throw std::invalid_argument("amips_frames: order must be 1..8");
  static std::unique_ptr<AmipsFrames> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] { cache[order] = std::make_unique<AmipsFrames>(order); });
  return *cache[order];
}

} // namespace curvetet::highorder

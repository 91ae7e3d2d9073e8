#include "curvetet/highorder/amips_frames.hpp"

#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quadrature.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace curvetet::highorder {

AmipsFrames::AmipsFrames(int order) {
  if (order < 1 || order > kMaxOrder) throw std::invalid_argument("AmipsFrames: order must be 1..8");
  // W: reference tet -> regular tet of unit edge (columns = its edge vectors).
  Eigen::Matrix3d w;
  w.col(0) << 1, 0, 0;
  w.col(1) << 0.5, std::sqrt(3.0) / 2, 0;
  w.col(2) << 0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0);
  const Eigen::Matrix3d w_inv = w.inverse();
  const Quadrature rule = tet_quadrature(order + 1);
  points_ = static_cast<int>(rule.points.size());
  nodes_ = tet_node_count(order);
  h_.reserve(static_cast<std::size_t>(points_) * nodes_);
  for (const auto& xi : rule.points) {
    const Eigen::MatrixXd g = lagrange_gradients(3, order, xi.data()) * w_inv; // row l = h_{l,q}^T
    for (int l = 0; l < nodes_; ++l) h_.push_back(g.row(l).transpose());
  }
}

void AmipsFrames::frames(const Eigen::Vector3d* nodes, Eigen::Matrix3d* frames) const {
  for (int q = 0; q < points_; ++q) {
    const Eigen::Vector3d* h = &h_[static_cast<std::size_t>(q) * nodes_];
    Eigen::Matrix3d k = Eigen::Matrix3d::Zero();
    for (int l = 0; l < nodes_; ++l) k.noalias() += nodes[l] * h[l].transpose();
    frames[q] = k;
  }
}

void AmipsFrames::add_direction(int local, double w, Eigen::Vector3d* c) const {
  for (int q = 0; q < points_; ++q) c[q] += w * h_[static_cast<std::size_t>(q) * nodes_ + local];
}

double AmipsFrames::max_amips(const Eigen::Matrix3d* frames, const Eigen::Vector3d* c, const Eigen::Vector3d& d,
                              double bound) const {
  const double bound_cubed = bound * bound * bound;
  double worst_cubed = 0;
  for (int q = 0; q < points_ && worst_cubed < bound_cubed; ++q) {
    Eigen::Matrix3d k = frames[q];
    if (c) k.noalias() += d * c[q].transpose();
    const double det = k.determinant();
    if (!(det > 0)) return std::numeric_limits<double>::infinity();
    const double n2 = k.squaredNorm();
    worst_cubed = std::max(worst_cubed, n2 * n2 * n2 / (27 * det * det));
  }
  return std::cbrt(worst_cubed);
}

const AmipsFrames& amips_frames(int order) {
  if (order < 1 || order > kMaxOrder) throw std::invalid_argument("amips_frames: order must be 1..8");
  static std::unique_ptr<AmipsFrames> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] { cache[order] = std::make_unique<AmipsFrames>(order); });
  return *cache[order];
}

} // namespace curvetet::highorder

#include "curvetet/highorder/amips_frames.hpp"

#include "curvetet/core/wide_vectors.hpp"
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

// The two products below are most of the optimizer's arithmetic: they get
// a wide-vector version; each sum keeps its order of operations, so both
// versions give the same bits.

namespace curvetet::highorder {

AmipsFrames::AmipsFrames(int order) {
  if (order < 1 || order > kMaxOrder) throw std::invalid_argument("AmipsFrames: order must be 1..8");
  // W: reference tet -> regular tet of unit edge (columns = its edge vectors).
  w_.col(0) << 1, 0, 0;
  w_.col(1) << 0.5, std::sqrt(3.0) / 2, 0;
  w_.col(2) << 0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0);
  const Eigen::Matrix3d w_inv = w_.inverse();
  const Eigen::Vector3d e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY(), e3 = Eigen::Vector3d::UnitZ();
  const Edges reference = {e1, e2, e3, e2 - e1, e3 - e1, e3 - e2};
  for (int i = 0; i < 6; ++i) edges_[i] = w_ * reference[i];
  nodes_ = tet_node_count(order);
  const std::vector<Eigen::Vector3d>& xis = quality_samples(order);
  points_ = static_cast<int>(xis.size());
  lattice_points_ = quality_lattice_points(order);
  // Rows padded with zeros to whole groups of kPanel (the products read
  // past 3 points_ and add zeros).
  stride_ = (3 * points_ + kPanel - 1) / kPanel * kPanel;
  h_.assign(static_cast<std::size_t>(nodes_) * stride_, 0.0);
  for (int q = 0; q < points_; ++q) {
    const Eigen::MatrixXd hq = lagrange_gradients(3, order, xis[q].data()) * w_inv;
    for (int l = 0; l < nodes_; ++l)
      for (int i = 0; i < 3; ++i) h_[static_cast<std::size_t>(l) * stride_ + 3 * q + i] = hq(l, i);
  }
}

CURVETET_WIDE_VECTORS void AmipsFrames::frames(const Eigen::Vector3d* nodes, Eigen::Matrix3d* frames, int points) const {
  // [K_0 K_1 ...] = X H (X = [x_0 ... x_n-1], 3 x n), kPanel columns of H
  // at a time with the 3 x kPanel block of sums in registers; an array of
  // column-major Matrix3d is that 3 x 3P column-major matrix.
  const int n = points < 0 ? points_ : std::min(points, points_);
  const int columns = 3 * n;
  double* out = frames[0].data();
  for (int b = 0; b * kPanel < columns; ++b) {
    double acc[3][kPanel] = {};
    for (int l = 0; l < nodes_; ++l) {
      const double* panel = &h_[static_cast<std::size_t>(l) * stride_ + b * kPanel];
      const double x0 = nodes[l].x(), x1 = nodes[l].y(), x2 = nodes[l].z();
      for (int j = 0; j < kPanel; ++j) {
        acc[0][j] += x0 * panel[j];
        acc[1][j] += x1 * panel[j];
        acc[2][j] += x2 * panel[j];
      }
    }
    const int width = std::min(kPanel, columns - b * kPanel);
    for (int j = 0; j < width; ++j)
      for (int r = 0; r < 3; ++r) out[3 * (b * kPanel + j) + r] = acc[r][j];
  }
}

CURVETET_WIDE_VECTORS void AmipsFrames::node_gradients(const Eigen::Matrix3d* dfdk, Eigen::Vector3d* out, int points) const {
  // out[l] = G H^T: the rows of G (3 x 3P) made contiguous and padded with
  // zeros to whole groups of kLanes, then kNodes nodes at a time, kLanes
  // partial sums per node and coordinate (in registers), added in a fixed order.
  constexpr int kNodes = 4, kLanes = 4;
  const int n = points < 0 ? points_ : std::min(points, points_);
  const int columns = 3 * n, padded = (columns + kLanes - 1) / kLanes * kLanes;
  thread_local std::vector<double> rows;
  rows.assign(3 * static_cast<std::size_t>(padded), 0.0);
  const double* g = dfdk[0].data();
  for (int j = 0; j < columns; ++j)
    for (int r = 0; r < 3; ++r) rows[r * padded + j] = g[3 * j + r];
  const double* g0 = rows.data();
  const double* g1 = g0 + padded;
  const double* g2 = g1 + padded;
  for (int l0 = 0; l0 < nodes_; l0 += kNodes) {
    const int count = std::min(kNodes, nodes_ - l0);
    double acc[kNodes][3][kLanes] = {};
    const double* h[kNodes];
    for (int i = 0; i < kNodes; ++i) h[i] = &h_[static_cast<std::size_t>(l0 + std::min(i, count - 1)) * stride_];
    for (int j = 0; j < padded; j += kLanes)
      for (int i = 0; i < kNodes; ++i)
        for (int t = 0; t < kLanes; ++t) {
          acc[i][0][t] += g0[j + t] * h[i][j + t];
          acc[i][1][t] += g1[j + t] * h[i][j + t];
          acc[i][2][t] += g2[j + t] * h[i][j + t];
        }
    for (int i = 0; i < count; ++i)
      for (int r = 0; r < 3; ++r) out[l0 + i][r] = (acc[i][r][0] + acc[i][r][1]) + (acc[i][r][2] + acc[i][r][3]);
  }
}

void AmipsFrames::add_direction(int local, double w, Eigen::Vector3d* c) const {
  const double* h = &h_[static_cast<std::size_t>(local) * stride_];
  for (int q = 0; q < points_; ++q) c[q] += w * Eigen::Vector3d(h[3 * q], h[3 * q + 1], h[3 * q + 2]);
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

void AmipsFrames::rank_one_terms(const Eigen::Matrix3d* frames, const Eigen::Vector3d* c, RankOneTerms* out,
                                 int points) const {
  const int n = points < 0 ? points_ : std::min(points, points_);
  for (int q = 0; q < n; ++q) {
    const Eigen::Matrix3d& k = frames[q];
    const Eigen::Vector3d x = k.col(1).cross(k.col(2)), y = k.col(2).cross(k.col(0)), z = k.col(0).cross(k.col(1));
    out[q] = {k.col(0).dot(x), k.squaredNorm(), c[q].squaredNorm(), k * c[q], c[q].x() * x + c[q].y() * y + c[q].z() * z};
  }
}

double AmipsFrames::max_amips(const RankOneTerms* terms, const Eigen::Vector3d& d, double bound, int points) const {
  const int n = points < 0 ? points_ : std::min(points, points_);
  const double bound_cubed = bound * bound * bound, d2 = d.squaredNorm();
  double worst_cubed = 0;
  for (int q = 0; q < n && worst_cubed < bound_cubed; ++q) {
    const RankOneTerms& t = terms[q];
    const double det = t.det + d.dot(t.cof_c);
    if (!(det > 0)) return std::numeric_limits<double>::infinity();
    const double n2 = t.norm2 + 2 * d.dot(t.kc) + d2 * t.c2;
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
  // (edges() holds W u):
  // d log sJ / dK = K^-T - sum_u (K W u)(W u)^T / |K W u|^2.
  const Eigen::Matrix3d j = k * w_;
  std::array<Eigen::Vector3d, 6> kwu;
  std::array<double, 6> length2;
  for (int e = 0; e < 6; ++e) {
    kwu[e] = k * edges_[e];
    length2[e] = kwu[e].squaredNorm();
  }
  double largest = -1;
  int corner = 0;
  for (int i = 0; i < 4; ++i) {
    double f = 1;
    for (int e : kCornerEdges[i]) f *= length2[e];
    if (f > largest) {
      largest = f;
      corner = i;
    }
  }
  Eigen::Matrix3d dlog = k.inverse().transpose();
  for (int e : kCornerEdges[corner]) dlog -= kwu[e] * edges_[e].transpose() / length2[e];
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

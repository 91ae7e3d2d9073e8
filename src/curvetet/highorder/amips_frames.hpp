#pragma once
// Quality of an order-P tet at the order-2P lattice of the quality
// convention (quality.hpp: the first quality_lattice_points(P) of
// quality_samples(P), corners and Lagrange nodes included), kept as frames so that the optimizer
// can try node moves without recomputing the Jacobians.
//
// Frame q of a tet with nodes x_l: K_q = J(xi_q) W^-1 = sum_l x_l h_{l,q}^T,
// h_{l,q} = W^-T grad phi_l(xi_q) (W as in quality.hpp). Moving node l by
// w_l d changes every frame by the rank-one term d c_q^T with
// c_q = sum_l w_l h_{l,q}, so a trial move costs one 3x3 update per point
// instead of a sum over all nodes. AMIPS(K) = |K|_F^2 / det(K)^(2/3) (3 for
// the regular tet, +inf when det K <= 0: quality.hpp's amips), max over all
// points, taken on AMIPS^3, which needs no cube root per point and has the
// same maximiser. The scaled Jacobian (quality.hpp) of J = K W, min over
// all points. Both equal tet_quality's.
#include <Eigen/Core>

#include <limits>
#include <vector>

namespace curvetet::highorder {

class AmipsFrames {
 public:
  explicit AmipsFrames(int order); // 1..8
  int num_points() const { return points_; } // the order-2P lattice
  int num_nodes() const { return nodes_; }

  // frames[q] = K_q for q < num_points(); nodes in internal (Gmsh) order.
  void frames(const Eigen::Vector3d* nodes, Eigen::Matrix3d* frames) const;
  // c[q] += w h_{local,q} for every point q.
  void add_direction(int local, double w, Eigen::Vector3d* c) const;

  // Max over all points of AMIPS(K_q + d c_q^T) (c == nullptr: of
  // K_q). Stops at the first point reaching `bound` (the result is then >= bound).
  double max_amips(const Eigen::Matrix3d* frames, const Eigen::Vector3d* c, const Eigen::Vector3d& d,
                   double bound = std::numeric_limits<double>::infinity()) const;
  // Min over all points of the scaled Jacobian of (K_q + d c_q^T) W. Stops
  // at the first point below `floor` (the result is then < floor).
  double min_scaled_jacobian(const Eigen::Matrix3d* frames, const Eigen::Vector3d* c, const Eigen::Vector3d& d,
                             double floor = -std::numeric_limits<double>::infinity()) const;

 private:
  int points_ = 0, nodes_ = 0;
  Eigen::Matrix3d w_;  // reference tet -> regular tet
  Eigen::MatrixXd h_;  // nodes_ x (3 points_): row l, columns 3q..3q+2 = h_{l,q}^T
};

// One table per order, built on first use (thread-safe).
const AmipsFrames& amips_frames(int order);

} // namespace curvetet::highorder

#pragma once
// Quality of an order-P tet at the sample points of the quality convention
// (quality.hpp's quality_samples(P): the order-2P lattice first, corners and
// Lagrange nodes included, then the degree-3(P-1) lattice's other points),
// kept as frames so that the optimizer can try node moves without
// recomputing the Jacobians. The measures can stop after the first
// `points` samples: the optimizer's trials use the order-2P lattice alone
// (2.3x cheaper at P = 4), its acceptance every sample.
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

#include <array>
#include <limits>
#include <vector>

namespace curvetet::highorder {

class AmipsFrames {
 public:
  explicit AmipsFrames(int order); // 1..8
  int num_points() const { return points_; }                 // every sample
  int num_lattice_points() const { return lattice_points_; } // the order-2P lattice's, first
  int num_nodes() const { return nodes_; }
  // W, the reference tet -> the regular tet of unit edge (J = K W).
  const Eigen::Matrix3d& reference_to_regular() const { return w_; }
  // W u for the reference tet's six edges u (up to sign), and the three of
  // them leaving each corner: the corner frames the scaled Jacobian compares.
  using Edges = std::array<Eigen::Vector3d, 6>;
  const Edges& edges() const { return edges_; }
  static constexpr std::array<std::array<int, 3>, 4> kCornerEdges = {{{0, 1, 2}, {0, 3, 4}, {1, 3, 5}, {2, 4, 5}}};

  // frames[q] = K_q for q < points (-1: num_points()); nodes in internal
  // (Gmsh) order.
  void frames(const Eigen::Vector3d* nodes, Eigen::Matrix3d* frames, int points = -1) const;
  // The gradient of a function of the frames of the first `points` points
  // (-1: all) with respect to the nodes: out[l] = sum_q dfdk[q] h_{l,q}
  // (dfdk[q] = d f / d K_q).
  void node_gradients(const Eigen::Matrix3d* dfdk, Eigen::Vector3d* out, int points = -1) const;
  // c[q] += w h_{local,q} for every point q.
  void add_direction(int local, double w, Eigen::Vector3d* c) const;

  // Max over points from <= q < `points` (-1: all) of AMIPS(K_q + d c_q^T)
  // (c == nullptr: of K_q); 0 for no point. Stops at the first point
  // reaching `bound` (the result is then >= bound).
  double max_amips(const Eigen::Matrix3d* frames, const Eigen::Vector3d* c, const Eigen::Vector3d& d,
                   double bound = std::numeric_limits<double>::infinity(), int points = -1, int from = 0) const;
  // Min over the same points of the scaled Jacobian of (K_q + d c_q^T) W
  // (+inf for no point). Stops at the first point below `floor` (the result
  // is then < floor).
  double min_scaled_jacobian(const Eigen::Matrix3d* frames, const Eigen::Vector3d* c, const Eigen::Vector3d& d,
                             double floor = -std::numeric_limits<double>::infinity(), int points = -1,
                             int from = 0) const;

  // For trials of many d on the same frames and directions: per point,
  // the terms that make AMIPS(K + d c^T) two dot products away
  // (|K + d c^T|^2 = |K|^2 + 2 d.(K c) + |d|^2 |c|^2 and, by the matrix
  // determinant lemma, det(K + d c^T) = det K + d.(cof(K) c)).
  struct RankOneTerms {
    double det, norm2, c2;
    Eigen::Vector3d kc, cof_c;
  };
  void rank_one_terms(const Eigen::Matrix3d* frames, const Eigen::Vector3d* c, RankOneTerms* out, int points) const;
  // max_amips(frames, c, d, bound, points) from those terms (equal up to rounding).
  double max_amips(const RankOneTerms* terms, const Eigen::Vector3d& d, double bound, int points) const;

  // Where the measures above are worst among the first `points` points
  // (-1: all): the index of the largest AMIPS / smallest scaled Jacobian,
  // its value in *value.
  int worst_amips_point(const Eigen::Matrix3d* frames, int points, double* value) const;
  int worst_scaled_jacobian_point(const Eigen::Matrix3d* frames, int points, double* value) const;
  // d/dd of AMIPS(K + d c^T) and of the scaled Jacobian of (K + d c^T) W at
  // d = 0 (K positive): the directions in which a move of weighted nodes
  // changes one point's measure fastest.
  Eigen::Vector3d amips_gradient(const Eigen::Matrix3d& k, const Eigen::Vector3d& c) const;
  Eigen::Vector3d scaled_jacobian_gradient(const Eigen::Matrix3d& k, const Eigen::Vector3d& c) const;

 private:
  int points_ = 0, lattice_points_ = 0, nodes_ = 0;
  Eigen::Matrix3d w_;  // reference tet -> regular tet
  Edges edges_;
  // h_{l,q}^T at entries l * stride_ + 3q .. 3q+2 (row-major, rows padded
  // with zeros): the products read it in order, with no packing per call.
  static constexpr int kPanel = 8;
  int stride_ = 0;
  std::vector<double> h_;
};

// One table per order, built on first use (thread-safe).
const AmipsFrames& amips_frames(int order);

} // namespace curvetet::highorder

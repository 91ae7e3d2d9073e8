#pragma once
// The joint descent's energy at the points of one tet (curved_descent.hpp):
// per point, (AMIPS / A0)^p plus, for each corner frame, (sJ0 / sJ)^p, and
// their derivatives by the point's frame K. The points are taken a block
// at a time, each quantity computed for the whole block in one loop, so
// that several points share a vector register (most of the descent's time
// is here).
#include <Eigen/Core>

#include <array>

namespace curvetet::volume {

struct DescentTerms {
  std::array<Eigen::Vector3d, 6> edges; // W u for the reference tet's edges (AmipsFrames::edges)
  double reference_det = 1;             // det W (J = K W)
  double amips_ref = 1, sj_ref = 1;     // A0, sJ0
  int power = 8;                        // p: even, >= 2

  // Sum of the terms over frames k[0..n), in point order; +inf when some
  // det K <= 0. With dk, dk[q] = d(terms of point q) / dK_q. Raises worst
  // to the largest AMIPS / A0 and sJ0 / sJ over the points.
  double operator()(const Eigen::Matrix3d* k, int n, Eigen::Matrix3d* dk, double& worst) const;
};

} // namespace curvetet::volume

#pragma once
// Element quality of curved tets and triangles (plain double, for ranking
// and reporting; validity is the certificate's job).
//
// Scaled Jacobian at a point xi, for each of the 4 corner frames v of the
// reference tet: sJ_v = sqrt(2) det J / (|a| |b| |c|), where a, b, c = J e
// for the three reference edges e leaving corner v. For a straight tet this
// is Verdict's scaled Jacobian (1 for the regular tet, <= 0 when inverted).
// min_scaled_jacobian = min over the Lagrange nodes and the quadrature points.
//
// AMIPS (tets): with J_r = J W^-1, W the map from the reference tet to the
// regular tet of unit edge, AMIPS = tr(J_r^T J_r) / (3 det(J_r)^(2/3)); 1 for
// a regular tet, +inf where det J <= 0. Reported as max and weighted mean
// over a conical-product quadrature with order+1 points per direction.
// MIPS (triangles in 3D): J_r = J W2^-1 (W2: reference -> unit equilateral),
// MIPS = tr(J_r^T J_r) / (2 sqrt(det(J_r^T J_r))); 1 for equilateral.
#include <Eigen/Core>

namespace curvetet::highorder {

struct TetQuality {
  double min_scaled_jacobian = 0;
  double max_amips = 0;
  double mean_amips = 0;
};

TetQuality tet_quality(int order, const Eigen::Vector3d* nodes);
// (The curved optimization's inner loop uses highorder/amips_frames.hpp.)

// Pointwise measures (J = dx/dxi, columns u, v, w).
double scaled_jacobian(const Eigen::Matrix3d& j);
double amips(const Eigen::Matrix3d& j);
double triangle_mips(const Eigen::Matrix<double, 3, 2>& j);

// Max MIPS of a curved triangle over quadrature points.
double triangle_max_mips(int order, const Eigen::Vector3d* nodes);

} // namespace curvetet::highorder

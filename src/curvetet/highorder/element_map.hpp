#pragma once
// Evaluation of curved Lagrange triangles and tetrahedra (nodes in internal =
// Gmsh order, orders 1..8) at reference points: position and first
// derivatives. Reference tet (0,0,0),(1,0,0),(0,1,0),(0,0,1); reference
// triangle (0,0),(1,0),(0,1). Plain double arithmetic (for sampling,
// quality and output, never for a guarantee: see jacobian_certificate.hpp).
#include <Eigen/Core>

namespace curvetet::highorder {

Eigen::Vector3d tet_point(int order, const Eigen::Vector3d* nodes, const Eigen::Vector3d& xi);
// Columns: dx/du, dx/dv, dx/dw.
Eigen::Matrix3d tet_jacobian(int order, const Eigen::Vector3d* nodes, const Eigen::Vector3d& xi);

Eigen::Vector3d triangle_point(int order, const Eigen::Vector3d* nodes, const Eigen::Vector2d& uv);
// Columns: dx/du, dx/dv.
Eigen::Matrix<double, 3, 2> triangle_jacobian(int order, const Eigen::Vector3d* nodes, const Eigen::Vector2d& uv);
// The same from the Lagrange gradients at the point (N x 2), for callers
// that keep them for many patches.
Eigen::Matrix<double, 3, 2> triangle_jacobian(const Eigen::MatrixXd& gradients, const Eigen::Vector3d* nodes);

} // namespace curvetet::highorder

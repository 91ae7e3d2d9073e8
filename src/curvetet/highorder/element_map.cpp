#include "curvetet/highorder/element_map.hpp"

#include "curvetet/highorder/bernstein.hpp"

namespace curvetet::highorder {

Eigen::Vector3d tet_point(int order, const Eigen::Vector3d* nodes, const Eigen::Vector3d& xi) {
  Eigen::VectorXd l = lagrange_basis(3, order, xi.data());
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < l.size(); ++i) x += l[i] * nodes[i];
  return x;
}

Eigen::Matrix3d tet_jacobian(int order, const Eigen::Vector3d* nodes, const Eigen::Vector3d& xi) {
  Eigen::MatrixXd g = lagrange_gradients(3, order, xi.data());
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  for (Eigen::Index i = 0; i < g.rows(); ++i) j += nodes[i] * g.row(i);
  return j;
}

Eigen::Vector3d triangle_point(int order, const Eigen::Vector3d* nodes, const Eigen::Vector2d& uv) {
  Eigen::VectorXd l = lagrange_basis(2, order, uv.data());
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < l.size(); ++i) x += l[i] * nodes[i];
  return x;
}

Eigen::Matrix<double, 3, 2> triangle_jacobian(int order, const Eigen::Vector3d* nodes, const Eigen::Vector2d& uv) {
  return triangle_jacobian(lagrange_gradients(2, order, uv.data()), nodes);
}

Eigen::Matrix<double, 3, 2> triangle_jacobian(const Eigen::MatrixXd& gradients, const Eigen::Vector3d* nodes) {
  Eigen::Matrix<double, 3, 2> j = Eigen::Matrix<double, 3, 2>::Zero();
  for (Eigen::Index i = 0; i < gradients.rows(); ++i) j += nodes[i] * gradients.row(i);
  return j;
}

} // namespace curvetet::highorder

#pragma once
// Quadrature on the reference tet and triangle with positive weights:
// Stroud's conical product (collapsed coordinates, Gauss-Legendre in each
// direction, Duffy Jacobian in the weights). With q points per direction it
// integrates polynomials of degree <= 2q-3 exactly. Computed in code.
#include <Eigen/Core>

#include <vector>

namespace curvetet::highorder {

struct Quadrature {
  std::vector<Eigen::Vector3d> points; // reference coordinates (z = 0 for triangles)
  std::vector<double> weights;         // sum = 1/6 (tet) or 1/2 (triangle)
};

// Gauss-Legendre nodes/weights on [0, 1].
void gauss_legendre(int q, std::vector<double>& x, std::vector<double>& w);
Quadrature tet_quadrature(int q);
Quadrature triangle_quadrature(int q);

} // namespace curvetet::highorder

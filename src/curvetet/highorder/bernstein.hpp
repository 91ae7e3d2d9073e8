#pragma once
// Bernstein (Bezier) polynomials on triangles and tetrahedra, and the exact
// change of basis to and from uniform Lagrange nodes.
//
// A degree-n Bernstein polynomial on a simplex of dimension d is
//   f(lambda) = sum_alpha c_alpha B_alpha(lambda),
//   B_alpha = n!/prod(alpha_i!) prod(lambda_i^alpha_i),
// with coefficients in the canonical order of simplex_lattice.hpp. The basis
// is non-negative and sums to 1, so min_alpha c_alpha <= f <= max_alpha c_alpha
// on the simplex, and the corner coefficients are the values at the corners.
//
// Lagrange <-> Bernstein: M[i][j] = B_j(node_i) (nodes in internal = Gmsh
// order, Bernstein in canonical order). Both M and A = M^-1 are computed once
// per (dim, order) with GMP rationals, i.e. exactly, then rounded to double
// (each entry within one ulp; the exact rationals stay available to the
// certificate's exact path inside this module). Orders 1..8.
#include "curvetet/highorder/simplex_lattice.hpp"

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace curvetet::highorder {

struct BasisChange {
  int dim = 0, order = 0;
  Eigen::MatrixXd lagrange_to_bernstein; // A: N x N, b = A * f (rows canonical, columns internal)
  Eigen::MatrixXd bernstein_to_lagrange; // M: N x N, f = M * b (rows internal, columns canonical)
  Eigen::MatrixXd abs_lagrange_to_bernstein; // |A|, for rounding-error bounds
};

// dim 2 (triangle) or 3 (tet), order 1..8; immutable, built on first use
// (thread-safe).
const BasisChange& basis_change(int dim, int order);

// Bernstein basis values at barycentric lambda (size d+1), canonical order.
std::vector<double> bernstein_basis(int dim, int degree, const double* lambda);
// Value of a Bernstein polynomial at lambda.
double bernstein_eval(int dim, int degree, const double* coeffs, const double* lambda);

// Lagrange basis (internal node order) at reference point xi (size dim) and
// its gradient d/dxi_k (N x dim, row i = node i).
Eigen::VectorXd lagrange_basis(int dim, int order, const double* xi);
Eigen::MatrixXd lagrange_gradients(int dim, int order, const double* xi);

// Coefficients (canonical, degree n-1) of d f / d xi_k, k = 1..dim, where xi_k
// = lambda_k and lambda_0 = 1 - sum xi: n (c_{beta+e_k} - c_{beta+e_0}).
std::vector<double> bernstein_derivative(int dim, int degree, const std::vector<double>& coeffs, int k);

// The same polynomial with degree n+1: c'_gamma = sum_k gamma_k/(n+1) c_{gamma-e_k}.
std::vector<double> degree_elevate(int dim, int degree, const std::vector<double>& coeffs);

// de Casteljau bisection of the simplex at the midpoint of its edge (a, b)
// (local vertex ids). first: the half keeping vertex a (b replaced by the
// midpoint), second: the half keeping b. Coefficients keep their meaning
// with respect to the child's vertices in the same slots.
std::pair<std::vector<double>, std::vector<double>> bisect(int dim, int degree, const std::vector<double>& coeffs,
                                                           int a, int b);

} // namespace curvetet::highorder

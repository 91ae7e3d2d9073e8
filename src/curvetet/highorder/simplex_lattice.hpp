#pragma once
// Multi-indices of a simplex lattice, the common index set of Bernstein
// coefficients and uniform Lagrange nodes.
//
// A simplex of dimension `dim` (2 = triangle, 3 = tetrahedron) and degree n
// has the multi-indices alpha = (alpha_0, ..., alpha_dim), alpha_i >= 0,
// sum = n. alpha_i pairs with barycentric coordinate lambda_i; on the unit
// reference simplex lambda_0 = 1 - sum(xi), lambda_k = xi_k (k >= 1), so the
// lattice point of alpha is xi = (alpha_1, ..., alpha_dim) / n.
//
// "Canonical order" (used for every Bernstein coefficient array in curvetet):
// lexicographic in (alpha_1, ..., alpha_dim) with alpha_dim varying fastest.
// Lagrange nodes are kept in Gmsh's order instead (node_ordering.hpp).
#include <array>
#include <cstdint>
#include <vector>

namespace curvetet::highorder {

using MultiIndex = std::array<int, 4>; // unused trailing entries are 0

class SimplexLattice {
 public:
  SimplexLattice(int dim, int degree);

  int dim() const { return dim_; }
  int degree() const { return degree_; }
  int size() const { return static_cast<int>(indices_.size()); }
  const MultiIndex& operator[](int i) const { return indices_[i]; }
  const std::vector<MultiIndex>& indices() const { return indices_; }

  // Canonical position of alpha (alpha_0 is implied by the others); -1 if
  // the entries are out of range.
  int index_of(const MultiIndex& alpha) const;
  // Multinomial n! / prod(alpha_i!) of entry i (exact: fits in a double for n <= 24).
  double multinomial(int i) const { return multinomials_[i]; }
  // Position of a corner (vertex v of the simplex: alpha_v = n).
  int corner(int v) const;

 private:
  int dim_, degree_;
  std::vector<MultiIndex> indices_;
  std::vector<int> lookup_; // (n+1)^dim table over (alpha_1..alpha_dim)
  std::vector<double> multinomials_;
};

// Immutable shared lattices, built once per (dim, degree) on first use.
// dim in {1, 2, 3} (1 = segment, used for the slab's t direction),
// 0 <= degree <= 24.
const SimplexLattice& lattice(int dim, int degree);

// Number of lattice points: C(degree + dim, dim).
int lattice_size(int dim, int degree);

} // namespace curvetet::highorder

#pragma once
// Internal to the highorder module (GMP types never leave its .cpp files):
// the exact rational Lagrange -> Bernstein matrix A (see bernstein.hpp).
#include <gmpxx.h>

#include <vector>

namespace curvetet::highorder::detail {

struct ExactBasisChange {
  int n = 0;                              // matrix size
  std::vector<mpq_class> to_bernstein;    // A, row-major n x n
  std::vector<mpq_class> to_lagrange;     // M, row-major n x n
};

// dim 2 or 3, order 1..8; built once, immutable.
const ExactBasisChange& exact_basis_change(int dim, int order);

} // namespace curvetet::highorder::detail

#pragma once
// Internal to the highorder module (GMP types never leave its .cpp files):
// Bernstein coefficients of det J for the certificate
// (jacobian_certificate.hpp explains the method and the rounding analysis).
//
// Coefficients live on (simplex of dimension sd, degree n) x ([0,1], degree
// q), flat index = simplex canonical index * (q + 1) + j. "Scaled"
// coefficients are multiplied by n!/alpha! * C(q, j), which turns Bernstein
// products into plain convolutions; signs are unchanged.
#include "curvetet/highorder/jacobian_certificate.hpp"

#include <gmpxx.h>

#include <vector>

namespace curvetet::highorder::detail {

inline constexpr double kUnit = 0x1p-53;     // unit roundoff of double
// Radii are sums and products of non-negative doubles, each output a chain
// of at most kMaxRadiusTerms operations (the largest is a convolution's sum
// over the pairs landing on one coefficient, checked where its table is
// built). Rounded to nearest, such a chain computes at least (1 - γ) times
// its exact value, γ = m u / (1 - m u) < 2^-32 for m ≤ 2^20 (Higham, §3.1);
// one more multiplication by kInflate ≥ (1 + 2^-31) / (1 - 2^-32) restores
// an upper bound, its own rounding included. Derived, not a margin.
inline constexpr int kMaxRadiusTerms = 1 << 20;
inline constexpr double kInflate = 1 + 1e-9;

struct Shape {
  int sd = 3, n = 0, q = 0;
  int simplex_count = 0, count = 0; // cached sizes (see make_shape)
  int simplex_size() const { return simplex_count; }
  int size() const { return count; }
};
Shape make_shape(int sd, int n, int q);

// n!/alpha! * C(q, j) per flat index (exact integers), built once per shape.
const std::vector<double>& weights(const Shape& s);

// Values with radii: |v[i] - exact[i]| <= r[i].
struct ScalarR {
  std::vector<double> v, r;
};

// Scaled det J coefficients: tets (shape (3, 3(P-1), 0)) and slabs (shape
// (2, 3k-2, 2), sign of the side applied), in double with radii or exactly.
ScalarR tet_scaled(int order, const Eigen::Vector3d* nodes);
std::vector<mpq_class> tet_scaled_exact(int order, const Eigen::Vector3d* nodes);
ScalarR slab_scaled(int k, const Eigen::Vector3d* middle, const std::array<Eigen::Vector3d, 3>& cap, SlabSide side,
                    MiddleBasis basis);
std::vector<mpq_class> slab_scaled_exact(int k, const Eigen::Vector3d* middle,
                                         const std::array<Eigen::Vector3d, 3>& cap, SlabSide side, MiddleBasis basis);

// Scaled -> plain Bernstein coefficients (division by the exact weights).
void unscale(const Shape& s, ScalarR& d);

} // namespace curvetet::highorder::detail

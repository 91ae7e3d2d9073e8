#include "curvetet/shell/exact_dot.hpp"

#include "curvetet/geometry/predicates.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace curvetet::shell {

namespace {

// Forward error of the double triple product of three rounded differences,
// relative to its permanent (the same expression with absolute values):
// Shewchuk's orient3d bound A, (7 + 56u) u with u = 2^-53 ("Adaptive
// Precision Floating-Point Arithmetic and Fast Robust Geometric
// Predicates", 1997, §4.3), valid without underflow, hence the floor on the
// permanent. tests/shell/test_exact_dot.cpp checks decisions against exact
// arithmetic on near-coplanar data.
constexpr double kUnit = 0x1p-53;
constexpr double kTripleProductError = (7 + 56 * kUnit) * kUnit;
constexpr double kNoUnderflow = 1e-250;

// (b - a) x (c - a) in rationals (exact: the inputs are doubles).
std::array<mpq_class, 3> exact_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  mpq_class u[3], v[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = mpq_class(b[i]) - mpq_class(a[i]);
    v[i] = mpq_class(c[i]) - mpq_class(a[i]);
  }
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

int exact_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& p,
               const Eigen::Vector3d& q) {
  const auto n = exact_normal(a, b, c);
  mpq_class det = 0;
  for (int i = 0; i < 3; ++i) det += n[i] * (mpq_class(q[i]) - mpq_class(p[i]));
  return sgn(det);
}

// Exact det[b - a, c - a, d - a] rounded to double. The 12 coordinates are
// integers times 2^e for the smallest exponent e among them, so the
// determinant is an integer polynomial (mpz: no gcd normalisation).
double exact_orient3d_value(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                           const Eigen::Vector3d& d) {
  const Eigen::Vector3d* p[4] = {&a, &b, &c, &d};
  int e = std::numeric_limits<int>::max();
  for (const auto* x : p)
    for (int i = 0; i < 3; ++i)
      if ((*x)[i] != 0) {
        int ex;
        std::frexp((*x)[i], &ex);
        e = std::min(e, ex - 53);
      }
  if (e == std::numeric_limits<int>::max()) return 0; // all zero
  mpz_class z[4][3];
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) {
      const double x = (*p[k])[i];
      if (x == 0) continue;
      int ex;
      const double m = std::frexp(x, &ex); // x = m 2^ex, |m| in [0.5, 1)
      z[k][i] = std::ldexp(m, 53);         // an integer of <= 53 bits
      mpz_mul_2exp(z[k][i].get_mpz_t(), z[k][i].get_mpz_t(), static_cast<unsigned long>(ex - 53 - e));
    }
  mpz_class e1[3], e2[3], e3[3];
  for (int i = 0; i < 3; ++i) {
    e1[i] = z[1][i] - z[0][i];
    e2[i] = z[2][i] - z[0][i];
    e3[i] = z[3][i] - z[0][i];
  }
  const mpz_class det = (e1[1] * e2[2] - e1[2] * e2[1]) * e3[0] + (e1[2] * e2[0] - e1[0] * e2[2]) * e3[1] +
                        (e1[0] * e2[1] - e1[1] * e2[0]) * e3[2];
  long exp2;
  const double mant = mpz_get_d_2exp(&exp2, det.get_mpz_t()); // truncated: relative error < 2^-52
  return std::ldexp(mant, static_cast<int>(exp2) + 3 * e);
}

} // namespace

int normal_dot_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, h = q - p;
  const double t0 = (e1[1] * e2[2] - e1[2] * e2[1]) * h[0];
  const double t1 = (e1[2] * e2[0] - e1[0] * e2[2]) * h[1];
  const double t2 = (e1[0] * e2[1] - e1[1] * e2[0]) * h[2];
  const double det = t0 + t1 + t2;
  const double permanent = (std::abs(e1[1] * e2[2]) + std::abs(e1[2] * e2[1])) * std::abs(h[0]) +
                           (std::abs(e1[2] * e2[0]) + std::abs(e1[0] * e2[2])) * std::abs(h[1]) +
                           (std::abs(e1[0] * e2[1]) + std::abs(e1[1] * e2[0])) * std::abs(h[2]);
  // Anything within the derived error (and underflow-sized values) goes to
  // exact arithmetic.
  const double bound = kTripleProductError * permanent;
  if (det > bound && permanent > kNoUnderflow) return 1;
  if (det < -bound && permanent > kNoUnderflow) return -1;
  return exact_sign(a, b, c, p, q);
}

int normals_dot_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     const Eigen::Vector3d& d, const Eigen::Vector3d& e, const Eigen::Vector3d& f) {
  const auto n = exact_normal(a, b, c), m = exact_normal(d, e, f);
  return sgn(n[0] * m[0] + n[1] * m[1] + n[2] * m[2]);
}

double orient3d_value(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d) {
  // A repeated point: exactly degenerate (common: shell middle vertices are
  // input vertices).
  if (d == a || d == b || d == c || a == b || a == c || b == c) return 0;
  const Eigen::Vector3d e1 = b - a, e2 = c - a, e3 = d - a;
  const double t0 = (e1[1] * e2[2] - e1[2] * e2[1]) * e3[0];
  const double t1 = (e1[2] * e2[0] - e1[0] * e2[2]) * e3[1];
  const double t2 = (e1[0] * e2[1] - e1[1] * e2[0]) * e3[2];
  const double det = t0 + t1 + t2;
  const double permanent = (std::abs(e1[1] * e2[2]) + std::abs(e1[2] * e2[1])) * std::abs(e3[0]) +
                           (std::abs(e1[2] * e2[0]) + std::abs(e1[0] * e2[2])) * std::abs(e3[1]) +
                           (std::abs(e1[0] * e2[1]) + std::abs(e1[1] * e2[0])) * std::abs(e3[2]);
  // The double value errs by at most kTripleProductError x permanent; it is
  // kept when that is at most 1e-12 of its magnitude.
  if (kTripleProductError * permanent <= 1e-12 * std::abs(det) && permanent > kNoUnderflow) return det;
  // Exactly coplanar points (flat regions: frequent) are told apart by the
  // fast filtered predicate before paying for rationals.
  if (geometry::orient3d(a, b, c, d) == 0) return 0;
  return exact_orient3d_value(a, b, c, d);
}

} // namespace curvetet::shell

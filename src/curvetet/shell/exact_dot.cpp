#include "curvetet/shell/exact_dot.hpp"

#include <gmpxx.h>

#include <cmath>

namespace curvetet::shell {

namespace {

int exact_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& p,
               const Eigen::Vector3d& q) {
  mpq_class e1[3], e2[3], h[3];
  for (int i = 0; i < 3; ++i) {
    e1[i] = mpq_class(b[i]) - mpq_class(a[i]);
    e2[i] = mpq_class(c[i]) - mpq_class(a[i]);
    h[i] = mpq_class(q[i]) - mpq_class(p[i]);
  }
  mpq_class det = (e1[1] * e2[2] - e1[2] * e2[1]) * h[0] + (e1[2] * e2[0] - e1[0] * e2[2]) * h[1] +
                  (e1[0] * e2[1] - e1[1] * e2[0]) * h[2];
  return sgn(det);
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
  // The rounded differences and products err by a few units in the last
  // place of `permanent`; 1e-14 (about 45 ulp) is a safe margin. Anything
  // closer (and underflow-sized values) goes to exact arithmetic.
  const double bound = 1e-14 * permanent;
  if (det > bound && permanent > 1e-250) return 1;
  if (det < -bound && permanent > 1e-250) return -1;
  return exact_sign(a, b, c, p, q);
}

} // namespace curvetet::shell

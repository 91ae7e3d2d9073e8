// The filtered predicates of shell/exact_dot agree with exact rational
// arithmetic on near-degenerate data built to sit inside the filter's error
// band (issue 27: no hand-picked tolerance decides a sign).
#include "curvetet/shell/exact_dot.hpp"

#include <Eigen/Geometry>
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <random>

using curvetet::shell::normal_dot_sign;
using curvetet::shell::orient3d_value;
using V = Eigen::Vector3d;

namespace {

mpq_class triple(const V& a, const V& b, const V& c, const V& p, const V& q) {
  mpq_class e1[3], e2[3], h[3];
  for (int i = 0; i < 3; ++i) {
    e1[i] = mpq_class(b[i]) - mpq_class(a[i]);
    e2[i] = mpq_class(c[i]) - mpq_class(a[i]);
    h[i] = mpq_class(q[i]) - mpq_class(p[i]);
  }
  return (e1[1] * e2[2] - e1[2] * e2[1]) * h[0] + (e1[2] * e2[0] - e1[0] * e2[2]) * h[1] +
         (e1[0] * e2[1] - e1[1] * e2[0]) * h[2];
}

V random_point(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return V(u(rng), u(rng), u(rng));
}

} // namespace

TEST(ExactDot, SignsAgreeWithRationalsOnNearlyCoplanarData) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> w(-2, 2);
  int zero = 0, nonzero = 0;
  for (int i = 0; i < 200000; ++i) {
    const double scale = i % 3 == 0 ? 1 : (i % 3 == 1 ? 1e3 : 1e-3);
    const V a = random_point(rng, scale), b = random_point(rng, scale), c = random_point(rng, scale);
    // q - p along the plane up to the rounding of its construction (and a
    // nudge of a few ulps every other time): the exact value lies within
    // the old 1e-14 band and often within the derived one.
    const V p = random_point(rng, scale);
    V q = p + w(rng) * (b - a) + w(rng) * (c - a);
    if (i % 2) q[i % 3] = std::nextafter(q[i % 3], q[i % 3] > 0 ? 2 * q[i % 3] : -2 * q[i % 3]);
    const int exact = sgn(triple(a, b, c, p, q));
    ASSERT_EQ(normal_dot_sign(a, b, c, p, q), exact) << i;
    (exact == 0 ? zero : nonzero) += 1;
    // orient3d_value: the same sign, exactly 0 on coplanar points.
    const double o = orient3d_value(a, b, c, q);
    const int exact_o = sgn(triple(a, b, c, a, q));
    ASSERT_EQ(o > 0 ? 1 : (o < 0 ? -1 : 0), exact_o) << i;
  }
  EXPECT_GT(nonzero, 1000);
}

TEST(ExactDot, OrientValueIsRelativelyAccurate) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 20000; ++i) {
    const V a = random_point(rng, 1), b = random_point(rng, 1), c = random_point(rng, 1);
    const V d = a + 0.3 * (b - a) + 0.4 * (c - a) + V(0, 0, std::ldexp(1.0, -40 - i % 20));
    const mpq_class exact = triple(a, b, c, a, d);
    const double got = orient3d_value(a, b, c, d);
    if (exact == 0) {
      EXPECT_EQ(got, 0);
      continue;
    }
    const mpq_class error = mpq_class(got) - exact;
    const double rel = std::abs(error.get_d() / exact.get_d());
    ASSERT_LE(rel, 1e-12) << i;
  }
}

// The straightening's orientation test (β locally injective): the normals of
// a triangle and of one built to contain that normal's direction are
// orthogonal up to rounding, where the double dot product guesses the sign.
TEST(ExactDot, NormalsDotSignIsExactWhereDoublesGuess) {
  std::mt19937_64 rng(3);
  auto cross = [](const V& u, const V& v) { return u.cross(v); };
  int disagreements = 0;
  for (int i = 0; i < 5000; ++i) {
    const V a = random_point(rng, 1), b = random_point(rng, 1), c = random_point(rng, 1), d = random_point(rng, 1);
    const V n = cross(b - a, c - a);
    const V e = d + n, f = d + (b - a);
    // Exact: (n_exact) . (m_exact), both normals from the rounded points.
    mpq_class nq[3], mq[3];
    auto exact_normal = [](const V& p, const V& q, const V& r, mpq_class* out) {
      mpq_class u[3], v[3];
      for (int k = 0; k < 3; ++k) {
        u[k] = mpq_class(q[k]) - mpq_class(p[k]);
        v[k] = mpq_class(r[k]) - mpq_class(p[k]);
      }
      out[0] = u[1] * v[2] - u[2] * v[1];
      out[1] = u[2] * v[0] - u[0] * v[2];
      out[2] = u[0] * v[1] - u[1] * v[0];
    };
    exact_normal(a, b, c, nq);
    exact_normal(d, e, f, mq);
    const int exact = sgn(nq[0] * mq[0] + nq[1] * mq[1] + nq[2] * mq[2]);
    const double in_doubles = n.dot(cross(e - d, f - d));
    disagreements += (in_doubles > 0) - (in_doubles < 0) != exact;
    ASSERT_EQ(curvetet::shell::normals_dot_sign(a, b, c, d, e, f), exact) << i;
  }
  EXPECT_GT(disagreements, 100); // the double formula really was a guess here
}

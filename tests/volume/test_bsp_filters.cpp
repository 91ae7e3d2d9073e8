// The BSP's double filters (volume/bsp_filters.hpp) against exact rational
// arithmetic on near-degenerate cases built to sit inside the rounding: a
// filter that decides must agree with the exact sign; with its derived bound
// shrunk 1024-fold it decides wrongly, so these cases do probe the bound.
#include "curvetet/volume/bsp_filters.hpp"
#include "curvetet/volume/homogeneous.hpp"

#include <gtest/gtest.h>

#include <random>

namespace curvetet {
namespace {

using namespace volume::exact;
using Eigen::Vector3d;

// A rational with a non-dyadic denominator, so approximate() rounds.
mpq_class rational(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> x(-scale, scale);
  std::uniform_int_distribution<int> den(3, 97);
  mpq_class q(x(rng));
  q /= den(rng) | 1;
  q.canonicalize();
  return q;
}

QPoint point(std::mt19937& rng, double scale) {
  QPoint p;
  for (auto& c : p.c) c = rational(rng, scale);
  return p;
}

Vector3d approx(const QPoint& p) { return approximate(to_h(p)); }

// a + s u + t v, exactly.
QPoint along(const QPoint& a, const mpq_class u[3], const mpq_class& s, const mpq_class v[3], const mpq_class& t) {
  QPoint x;
  for (int i = 0; i < 3; ++i) x.c[i] = a.c[i] + s * u[i] + t * v[i];
  return x;
}

void cross(const mpq_class u[3], const mpq_class v[3], mpq_class out[3]) {
  out[0] = u[1] * v[2] - u[2] * v[1];
  out[1] = u[2] * v[0] - u[0] * v[2];
  out[2] = u[0] * v[1] - u[1] * v[0];
}

// Exact offsets 0 and ±2^-k for k up to 80: inside and around the rounding.
mpq_class tiny(std::mt19937& rng) {
  std::uniform_int_distribution<int> k(40, 80), s(-1, 1);
  mpq_class t(s(rng));
  mpz_class d = 1;
  d <<= k(rng);
  return t / d;
}

struct Tally {
  int decided = 0, wrong = 0;
  void add(int filtered, int exact) {
    if (filtered == 0) return;
    ++decided;
    wrong += filtered != exact;
  }
};

TEST(BspFilters, SideOfAPlaneAgreesWithExactSigns) {
  std::mt19937 rng(7);
  Tally derived, shrunk;
  for (int k = 0; k < 20000; ++k) {
    const double scale = std::ldexp(1.0, k % 40 - 20);
    const Vector3d a(std::uniform_real_distribution<double>(-scale, scale)(rng), scale / 3, -scale / 7);
    QPoint qa{{mpq_class(a[0]), mpq_class(a[1]), mpq_class(a[2])}};
    const QPoint b = point(rng, scale), c = point(rng, scale);
    mpq_class u[3], v[3], n[3];
    for (int i = 0; i < 3; ++i) u[i] = b.c[i] - qa.c[i], v[i] = c.c[i] - qa.c[i];
    cross(u, v, n);
    Vector3d nd;
    for (int i = 0; i < 3; ++i) nd[i] = n[i].get_d(); // toward zero
    const mpq_class t = tiny(rng);
    QPoint x = along(qa, u, rational(rng, 1), v, rational(rng, 1));
    for (int i = 0; i < 3; ++i) x.c[i] += t * n[i];
    const int exact = sgn(t);
    derived.add(side_filter(nd, nd.lpNorm<1>(), a, approx(x)), exact);
    shrunk.add(side_filter(nd, nd.lpNorm<1>(), a, approx(x), kSideFactor / 1024), exact);
  }
  EXPECT_EQ(derived.wrong, 0);
  EXPECT_GT(derived.decided, 1000);
  EXPECT_GT(shrunk.wrong, 0);
}

TEST(BspFilters, OrientationInAPlaneAgreesWithExactSigns) {
  std::mt19937 rng(11);
  Tally derived, shrunk, collinear_derived, collinear_shrunk;
  for (int k = 0; k < 20000; ++k) {
    const double scale = std::ldexp(1.0, k % 40 - 20);
    const QPoint p = point(rng, scale), q = point(rng, scale), r = point(rng, scale);
    mpq_class u[3], w[3], n[3], side[3];
    for (int i = 0; i < 3; ++i) u[i] = q.c[i] - p.c[i], w[i] = r.c[i] - p.c[i];
    cross(u, w, n);   // the plane of p, q, r
    cross(n, u, side); // in that plane, across the line pq
    Vector3d nd;
    for (int i = 0; i < 3; ++i) nd[i] = n[i].get_d();
    const mpq_class t = tiny(rng);
    const QPoint x = along(p, u, rational(rng, 1), side, t);
    // ((q - p) x (t n x u)) . n = t (|n|^2 |u|^2 - (u . n)^2) and u . n = 0.
    const int exact = sgn(t);
    const Vector3d pd = approx(p), qd = approx(q), xd = approx(x);
    derived.add(orient_in_plane_filter(pd, qd, xd, nd, nd.lpNorm<1>()), exact);
    shrunk.add(orient_in_plane_filter(pd, qd, xd, nd, nd.lpNorm<1>(), kOrientFactor / 1024), exact);
    collinear_derived.add(not_collinear_filter(pd, qd, xd), t != 0);
    collinear_shrunk.add(not_collinear_filter(pd, qd, xd, kOrientFactor / 1024), t != 0);
  }
  EXPECT_EQ(derived.wrong, 0);
  EXPECT_EQ(collinear_derived.wrong, 0);
  EXPECT_GT(derived.decided, 1000);
  EXPECT_GT(collinear_derived.decided, 1000);
  EXPECT_GT(shrunk.wrong + collinear_shrunk.wrong, 0);
}

TEST(BspFilters, PaddedBoxesHoldTheExactPoints) {
  std::mt19937 rng(3);
  for (int k = 0; k < 20000; ++k) {
    const QPoint p = point(rng, std::ldexp(1.0, k % 60 - 30));
    const Vector3d d = approx(p);
    const double pad = approximation_pad(d.cwiseAbs().maxCoeff());
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(cmp(mpq_class(d[i] - pad), p.c[i]), 0);
      EXPECT_GE(cmp(mpq_class(d[i] + pad), p.c[i]), 0);
    }
  }
}

} // namespace
} // namespace curvetet

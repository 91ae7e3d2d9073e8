// The BSP's integer (homogeneous) predicates against the same quantities in
// mpq arithmetic, on random rational points and planes, including points
// exactly on the plane or on the line (the cases the floating filters leave
// to them).
#include "curvetet/volume/homogeneous.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace curvetet {
namespace {

using namespace volume::exact;

mpq_class random_rational(std::mt19937& rng) {
  std::uniform_int_distribution<long> num(-1000000, 1000000), den(1, 999983);
  mpq_class q(num(rng), den(rng));
  q.canonicalize();
  return q;
}

QPoint random_point(std::mt19937& rng) {
  QPoint p;
  for (auto& c : p.c) c = random_rational(rng);
  return p;
}

QPoint affine(const QPoint& a, const QPoint& b, const mpq_class& t) {
  QPoint p;
  for (int i = 0; i < 3; ++i) p.c[i] = a.c[i] + t * (b.c[i] - a.c[i]);
  return p;
}

mpq_class plane_value(const QPoint& a, const mpq_class n[3], const QPoint& x) {
  mpq_class s;
  for (int i = 0; i < 3; ++i) s += n[i] * (x.c[i] - a.c[i]);
  return s;
}

bool same(const QPoint& a, const QPoint& b) {
  return a.c[0] == b.c[0] && a.c[1] == b.c[1] && a.c[2] == b.c[2];
}

TEST(VolumeHomogeneous, RoundTripAndNormalizedForm) {
  std::mt19937 rng(7);
  for (int k = 0; k < 200; ++k) {
    const QPoint q = random_point(rng);
    HPoint h = to_h(q);
    ASSERT_GT(sgn(h.w), 0);
    EXPECT_TRUE(same(to_q(h), q));
    // Scaled by a common factor: normalize restores the primitive form.
    HPoint scaled = h;
    for (auto& x : scaled.x) x *= 12345;
    scaled.w *= 12345;
    normalize(scaled);
    EXPECT_EQ(scaled.w, h.w);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(scaled.x[i], h.x[i]);
    const Vec3 d = approximate(h);
    for (int i = 0; i < 3; ++i) EXPECT_LE(std::abs(d[i] - q.c[i].get_d()), 4e-16 * std::abs(q.c[i].get_d()));
  }
}

TEST(VolumeHomogeneous, SidesAndCrossingsMatchRationalArithmetic) {
  std::mt19937 rng(11);
  int on_plane = 0;
  for (int k = 0; k < 300; ++k) {
    const QPoint a = random_point(rng), p = random_point(rng);
    mpq_class n[3];
    for (auto& c : n) c = random_rational(rng);
    const HPlane plane = to_hplane(a, n);
    // A point on the plane: a plus a vector orthogonal to n.
    QPoint on = a;
    on.c[0] += n[1];
    on.c[1] -= n[0];
    for (const QPoint* x : {&p, static_cast<const QPoint*>(&on), &a}) {
      const int expected = sgn(plane_value(a, n, *x));
      EXPECT_EQ(sgn(value(plane, to_h(*x))), expected);
      on_plane += expected == 0;
    }
    // The crossing of a segment with opposite ends is the rational one.
    const QPoint q = affine(on, p, mpq_class(-3, 7)); // p and q on opposite sides
    const mpz_class vp = value(plane, to_h(p)), vq = value(plane, to_h(q));
    if (sgn(vp) == 0) continue;
    ASSERT_EQ(sgn(vp), -sgn(vq));
    HPoint w = crossing(to_h(p), to_h(q), vp, vq);
    normalize(w);
    EXPECT_TRUE(same(to_q(w), on));
  }
  EXPECT_GE(on_plane, 600);
}

TEST(VolumeHomogeneous, OrientInPlaneMatchesRationalArithmetic) {
  std::mt19937 rng(13);
  for (int k = 0; k < 300; ++k) {
    const QPoint p = random_point(rng), q = random_point(rng);
    mpq_class n[3];
    for (auto& c : n) c = random_rational(rng);
    mpz_class ni[3];
    const mpq_class scale(7, 3); // any positive multiple of n gives the same sign
    for (int i = 0; i < 3; ++i) {
      mpq_class s = n[i] * scale * 3 * n[0].get_den() * n[1].get_den() * n[2].get_den();
      ASSERT_EQ(s.get_den(), 1);
      ni[i] = s.get_num();
    }
    for (const QPoint& x : {random_point(rng), affine(p, q, mpq_class(5, 11))}) {
      mpq_class u[3], w[3];
      for (int i = 0; i < 3; ++i) {
        u[i] = q.c[i] - p.c[i];
        w[i] = x.c[i] - p.c[i];
      }
      const mpq_class expected = (u[1] * w[2] - u[2] * w[1]) * n[0] + (u[2] * w[0] - u[0] * w[2]) * n[1] +
                                 (u[0] * w[1] - u[1] * w[0]) * n[2];
      EXPECT_EQ(orient_in_plane(to_h(p), to_h(q), to_h(x), ni), sgn(expected));
    }
  }
}

mpq_class det_reference(const QPoint& a, const QPoint& b, const QPoint& c, const QPoint& d) {
  mpq_class u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = b.c[i] - a.c[i];
    v[i] = c.c[i] - a.c[i];
    w[i] = d.c[i] - a.c[i];
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

TEST(VolumeHomogeneous, Orient3dOnRationalPointsIsExact) {
  std::mt19937 rng(17);
  int signs[3] = {0, 0, 0};
  for (int k = 0; k < 200; ++k) {
    const QPoint a = random_point(rng), b = random_point(rng), c = random_point(rng);
    // d on the plane abc, then pushed off it either way by a tiny amount.
    const QPoint on = affine(affine(a, b, mpq_class(2, 9)), c, mpq_class(-4, 5));
    EXPECT_EQ(orient3d(a, b, c, on), 0);
    for (const mpq_class& push : {mpq_class(1, 1000000007), mpq_class(-1, 999999937)}) {
      QPoint d = on;
      d.c[k % 3] += push;
      const int expected = sgn(det_reference(a, b, c, d));
      EXPECT_EQ(orient3d(a, b, c, d), expected);
      ++signs[expected + 1];
    }
  }
  EXPECT_GT(signs[0], 0);
  EXPECT_GT(signs[2], 0);
}

} // namespace
} // namespace curvetet

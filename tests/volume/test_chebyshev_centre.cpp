// The double-precision Chebyshev centre (volume/chebyshev_centre.hpp)
// against known answers: a cube, a tetrahedron, and half-spaces with no
// common interior.
#include "curvetet/volume/chebyshev_centre.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace curvetet {
namespace {

using mesh::Vec3;
using volume::HalfSpace;

std::vector<HalfSpace> cube(const Vec3& lo, const Vec3& hi) {
  std::vector<HalfSpace> h;
  for (int d = 0; d < 3; ++d) {
    h.push_back({Vec3::Unit(d), lo[d]});
    h.push_back({-Vec3::Unit(d), -hi[d]});
  }
  return h;
}

TEST(ChebyshevCentre, BoxOfHalfSpacesHasItsCentreAndHalfItsShortestSide) {
  const Vec3 lo(1, -2, 3), hi(3, 5, 3.5);
  const auto c = volume::chebyshev_centre(cube(lo, hi), lo - Vec3::Constant(1), hi + Vec3::Constant(1));
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->radius, 0.25, 1e-12);
  EXPECT_NEAR(c->point.z(), 3.25, 1e-12);
  EXPECT_TRUE((c->point.array() > lo.array()).all() && (c->point.array() < hi.array()).all());
}

// A tetrahedron's inscribed ball: centre at the incentre, radius 3V / area.
TEST(ChebyshevCentre, TetrahedronGivesItsInscribedBallAtAnyPlaceAndScale) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 100; ++trial) {
    const double scale = std::pow(10.0, 3 * u(rng));
    const Vec3 shift = 1e3 * Vec3(u(rng), u(rng), u(rng));
    Vec3 x[4];
    for (auto& p : x) p = shift + scale * Vec3(u(rng), u(rng), u(rng));
    const double volume = (x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0])) / 6;
    if (std::abs(volume) < 1e-3 * scale * scale * scale) continue;
    if (volume < 0) std::swap(x[1], x[2]);
    std::vector<HalfSpace> h;
    double area = 0;
    Vec3 incentre = Vec3::Zero();
    for (int k = 0; k < 4; ++k) {
      const Vec3 &a = x[(k + 1) % 4], &b = x[(k + 2) % 4], &c = x[(k + 3) % 4];
      Vec3 n = (b - a).cross(c - a);
      if (n.dot(x[k] - a) < 0) n = -n; // towards the opposite corner: inside
      area += 0.5 * n.norm();
      incentre += 0.5 * n.norm() * x[k];
      h.push_back({n.normalized(), n.normalized().dot(a)});
    }
    incentre /= area;
    Vec3 lo = x[0], hi = x[0];
    for (const auto& p : x) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const auto c = volume::chebyshev_centre(h, lo, hi);
    ASSERT_TRUE(c) << trial;
    const double radius = 3 * std::abs(volume) / area;
    EXPECT_NEAR(c->radius, radius, 1e-9 * scale) << trial;
    EXPECT_LE((c->point - incentre).norm(), 1e-8 * scale) << trial;
  }
}

TEST(ChebyshevCentre, DisjointHalfSpacesGiveANegativeRadius) {
  // x >= 1 and x <= -1: the best point is halfway, 1 from both.
  const std::vector<HalfSpace> h{{Vec3::UnitX(), 1}, {-Vec3::UnitX(), 1}};
  const auto c = volume::chebyshev_centre(h, Vec3::Constant(-4), Vec3::Constant(4));
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->radius, -1, 1e-12);
  EXPECT_NEAR(c->point.x(), 0, 1e-12);
}

} // namespace
} // namespace curvetet

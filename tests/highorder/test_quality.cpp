// Quality measures: 1 on the regular tet / equilateral triangle, Verdict's
// value 1/sqrt(2) on the right-angle unit tet, negative / infinite on an
// inverted tet; quadrature weights sum to the reference volume.
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/quadrature.hpp"
#include "curvetet/highorder/quality.hpp"

#include "element_fixtures.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace curvetet::highorder;
using namespace curvetet::highorder::testing;

TEST(Quality, RegularRightAndInvertedTets) {
  const std::array<Eigen::Vector3d, 4> regular = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                                  Eigen::Vector3d(0.5, std::sqrt(3.0) / 2, 0),
                                                  Eigen::Vector3d(0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0))};
  for (int p = 1; p <= 4; ++p) {
    auto q = tet_quality(p, straight_tet(p, regular).data());
    EXPECT_NEAR(q.min_scaled_jacobian, 1.0, 1e-9);
    EXPECT_NEAR(q.max_amips, 1.0, 1e-9);
    EXPECT_NEAR(q.mean_amips, 1.0, 1e-9);
    auto r = tet_quality(p, straight_tet(p).data());
    EXPECT_NEAR(r.min_scaled_jacobian, 1 / std::sqrt(2.0), 1e-9);
    EXPECT_GT(r.max_amips, 1.0);
    auto inv = straight_tet(p, {regular[1], regular[0], regular[2], regular[3]});
    auto i = tet_quality(p, inv.data());
    EXPECT_NEAR(i.min_scaled_jacobian, -1.0, 1e-9);
    EXPECT_TRUE(std::isinf(i.max_amips));
  }
  auto curved = mapped_tet(3, regular, gentle_bend);
  auto c = tet_quality(3, curved.data());
  EXPECT_GT(c.min_scaled_jacobian, 0.5);
  EXPECT_LT(c.min_scaled_jacobian, 1.0);
  EXPECT_GE(c.mean_amips, 1.0);
  EXPECT_GE(c.max_amips, c.mean_amips);
}

TEST(Quality, EquilateralTriangleMips) {
  std::vector<Eigen::Vector3d> tri = {{0, 0, 1}, {1, 0, 1}, {0.5, std::sqrt(3.0) / 2, 1}};
  EXPECT_NEAR(triangle_max_mips(1, tri.data()), 1.0, 1e-12);
  tri[2] = {0.5, 0.2, 1};
  EXPECT_GT(triangle_max_mips(1, tri.data()), 1.5);
}

TEST(Quadrature, WeightsAndExactness) {
  // q points per direction: exact up to degree 2q-3 (so the volume needs q >= 2).
  for (int q = 2; q <= 6; ++q) {
    auto t = tet_quadrature(q);
    double s = 0, m = 0;
    for (std::size_t i = 0; i < t.points.size(); ++i) {
      s += t.weights[i];
      m += t.weights[i] * t.points[i].x() * t.points[i].y(); // int x y = 1/120
    }
    EXPECT_NEAR(s, 1.0 / 6.0, 1e-14);
    if (q >= 3) EXPECT_NEAR(m, 1.0 / 120.0, 1e-14);
    auto tr = triangle_quadrature(q);
    double a = 0;
    for (double w : tr.weights) a += w;
    EXPECT_NEAR(a, 0.5, 1e-14);
  }
}

// Quality measures in the convention of quality.hpp (validate.py's): AMIPS 3
// and scaled Jacobian 1 on the regular tet (at every sample point), MIPS 1
// on the equilateral triangle, Verdict's value 1/sqrt(2) on the right-angle
// unit tet, negative / infinite on an inverted tet; the samples are the
// order-2P lattice with its corners and the degree-3(P-1) lattice (as
// validate.py samples), so a worst corner is seen; quadrature
// weights sum to the reference volume.
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/quadrature.hpp"
#include "curvetet/highorder/quality.hpp"

#include "element_fixtures.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

using namespace curvetet::highorder;
using namespace curvetet::highorder::testing;

TEST(Quality, RegularRightAndInvertedTets) {
  const std::array<Eigen::Vector3d, 4> regular = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                                  Eigen::Vector3d(0.5, std::sqrt(3.0) / 2, 0),
                                                  Eigen::Vector3d(0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0))};
  for (int p = 1; p <= 4; ++p) {
    auto q = tet_quality(p, straight_tet(p, regular).data());
    EXPECT_NEAR(q.min_scaled_jacobian, 1.0, 1e-9);
    EXPECT_NEAR(q.max_amips, 3.0, 1e-9);
    EXPECT_NEAR(q.mean_amips, 3.0, 1e-9);
    auto r = tet_quality(p, straight_tet(p).data());
    EXPECT_NEAR(r.min_scaled_jacobian, 1 / std::sqrt(2.0), 1e-9);
    EXPECT_GT(r.max_amips, 3.0);
    auto inv = straight_tet(p, {regular[1], regular[0], regular[2], regular[3]});
    auto i = tet_quality(p, inv.data());
    EXPECT_NEAR(i.min_scaled_jacobian, -1.0, 1e-9);
    EXPECT_TRUE(std::isinf(i.max_amips));
  }
  auto curved = mapped_tet(3, regular, gentle_bend);
  auto c = tet_quality(3, curved.data());
  EXPECT_GT(c.min_scaled_jacobian, 0.5);
  EXPECT_LT(c.min_scaled_jacobian, 1.0);
  EXPECT_GE(c.mean_amips, 3.0);
  EXPECT_GE(c.max_amips, c.mean_amips);
}

const std::array<Eigen::Vector3d, 4> kRegular = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                                 Eigen::Vector3d(0.5, std::sqrt(3.0) / 2, 0),
                                                 Eigen::Vector3d(0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0))};

// The samples are validate.py's: the order-2P lattice, corners included
// (its tet_lattice(2P)), and the degree-3(P-1) lattice, each point once;
// order 1 is one point.
TEST(Quality, SamplesAreTheOrder2PAndDegree3PMinus1Lattices) {
  EXPECT_EQ(quality_samples(1).size(), 1u);
  for (int p = 2; p <= 8; ++p) {
    const auto& s = quality_samples(p);
    const auto has = [&](const Eigen::Vector3d& y) {
      return std::count_if(s.begin(), s.end(), [&](const Eigen::Vector3d& x) { return (x - y).norm() < 1e-13; });
    };
    const auto size = [](int m) { return (m + 1) * (m + 2) * (m + 3) / 6; };
    const int a = 2 * p, b = 3 * (p - 1), g = std::gcd(a, b);
    EXPECT_EQ(static_cast<int>(s.size()), size(a) + size(b) - size(g)) << "order " << p;
    for (int m : {a, b})
      for (int i = 0; i <= m; ++i)
        for (int j = 0; i + j <= m; ++j)
          for (int l = 0; i + j + l <= m; ++l) EXPECT_EQ(has(Eigen::Vector3d(i, j, l) / m), 1) << "order " << p;
  }
}

// The regular tet, as a straight tet of order P and as a (slightly) curved
// one whose nodes are not where the straight test expects: AMIPS 3 and
// scaled Jacobian 1 at every sample, at any scale.
TEST(Quality, RegularTetIsThreeAndOneAtEverySample) {
  for (int p = 1; p <= 5; ++p)
    for (double scale : {1e-6, 1.0, 1e4}) {
      auto nodes = straight_tet(p, kRegular);
      for (auto& x : nodes) x *= scale;
      for (const auto& xi : quality_samples(p)) {
        const Eigen::Matrix3d j = tet_jacobian(p, nodes.data(), xi);
        EXPECT_NEAR(amips(j), 3.0, 1e-9) << "order " << p;
        EXPECT_NEAR(scaled_jacobian(j), 1.0, 1e-9) << "order " << p;
      }
      const TetQuality q = tet_quality(p, nodes.data());
      EXPECT_NEAR(q.max_amips, 3.0, 1e-9);
      EXPECT_NEAR(q.mean_amips, 3.0, 1e-9);
      EXPECT_NEAR(q.min_scaled_jacobian, 1.0, 1e-9);
    }
}

// An order-2 regular tet whose midpoint node of edge 0-1 slides 0.15 toward
// corner 1: J is affine in xi and most distorted at the corners 0 and 1,
// where every quadrature point misses it. The reported max AMIPS and min
// scaled Jacobian are the corner values (no larger, no smaller anywhere on
// a fine lattice), strictly worse than the quadrature points' (the old
// sampling).
TEST(Quality, WorstCornerIsReportedAtItsValue) {
  auto nodes = straight_tet(2, kRegular);
  int mid01 = -1;
  for (int i = 4; i < static_cast<int>(nodes.size()); ++i)
    if ((nodes[i] - 0.5 * (kRegular[0] + kRegular[1])).norm() < 1e-12) mid01 = i;
  ASSERT_GE(mid01, 4);
  nodes[mid01] += 0.15 * (kRegular[1] - kRegular[0]);
  double corner_amips = 0, corner_sj = 1e300;
  for (const Eigen::Vector3d xi : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                   Eigen::Vector3d(0, 0, 1)}) {
    const Eigen::Matrix3d j = tet_jacobian(2, nodes.data(), xi);
    corner_amips = std::max(corner_amips, amips(j));
    corner_sj = std::min(corner_sj, scaled_jacobian(j));
  }
  const TetQuality q = tet_quality(2, nodes.data());
  EXPECT_DOUBLE_EQ(q.max_amips, corner_amips);
  EXPECT_DOUBLE_EQ(q.min_scaled_jacobian, corner_sj);
  // Nowhere worse (an order-16 lattice).
  const int m = 16;
  for (int a = 0; a <= m; ++a)
    for (int b = 0; a + b <= m; ++b)
      for (int c = 0; a + b + c <= m; ++c) {
        const Eigen::Matrix3d j = tet_jacobian(2, nodes.data(), Eigen::Vector3d(a, b, c) / m);
        EXPECT_LE(amips(j), corner_amips * (1 + 1e-12));
        EXPECT_GE(scaled_jacobian(j), corner_sj * (1 - 1e-12));
      }
  // The quadrature points see less.
  double quadrature_amips = 0;
  for (const auto& xi : tet_quadrature(3).points)
    quadrature_amips = std::max(quadrature_amips, amips(tet_jacobian(2, nodes.data(), xi)));
  EXPECT_LT(quadrature_amips, corner_amips * 0.99);
  // The mean is the plain mean over the samples.
  double sum = 0;
  for (const auto& xi : quality_samples(2)) sum += amips(tet_jacobian(2, nodes.data(), xi));
  EXPECT_NEAR(q.mean_amips, sum / static_cast<double>(quality_samples(2).size()), 1e-12 * q.mean_amips);
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

// scaled_jacobian takes one square root (the corner frame with the largest
// product when det > 0, the smallest positive one otherwise): it must equal
// the min over the four corners of sqrt(2) det / sqrt(product), +-1 for a
// degenerate frame, bit for bit, whatever the sign of det.
TEST(Quality, ScaledJacobianIsTheMinOverTheFourCorners) {
  const auto reference = [](const Eigen::Matrix3d& j) {
    const double det = j.determinant();
    const Eigen::Vector3d a = j.col(0), b = j.col(1), c = j.col(2);
    const double aa = a.squaredNorm(), bb = b.squaredNorm(), cc = c.squaredNorm();
    const double ab = (b - a).squaredNorm(), ac = (c - a).squaredNorm(), bc = (c - b).squaredNorm();
    double best = std::numeric_limits<double>::infinity();
    for (double f : {aa * bb * cc, aa * ab * ac, bb * ab * bc, cc * ac * bc})
      best = std::min(best, f > 0 ? std::sqrt(2.0) * det / std::sqrt(f) : (det > 0 ? 1.0 : -1.0));
    return best;
  };
  std::vector<Eigen::Matrix3d> cases;
  for (int s = 0; s < 200; ++s) cases.push_back(Eigen::Matrix3d::Random() * (1 + s % 7));
  Eigen::Matrix3d flat = Eigen::Matrix3d::Random();
  flat.col(2) = flat.col(0) + flat.col(1); // det 0
  cases.push_back(flat);
  Eigen::Matrix3d repeated = Eigen::Matrix3d::Random();
  repeated.col(1) = repeated.col(0); // a degenerate corner frame (|b - a| = 0)
  cases.push_back(repeated);
  cases.push_back(Eigen::Matrix3d::Zero());
  int negative = 0;
  for (const auto& j : cases) {
    EXPECT_EQ(scaled_jacobian(j), reference(j)) << j;
    negative += j.determinant() < 0;
  }
  EXPECT_GT(negative, 20); // both signs exercised
}

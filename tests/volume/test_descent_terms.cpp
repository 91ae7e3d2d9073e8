// The joint descent's per-point terms, taken a block of points at a time
// (volume/descent_terms.hpp): equal to their definition point by point, the
// gradient equal to central differences, +inf at a non-positive frame.
#include "curvetet/highorder/amips_frames.hpp"
#include "curvetet/volume/descent_terms.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace curvetet;
using Mat3 = Eigen::Matrix3d;

namespace {

volume::DescentTerms terms(int power) {
  const auto& frames = highorder::amips_frames(4);
  volume::DescentTerms s;
  s.edges = frames.edges();
  s.reference_det = frames.reference_to_regular().determinant();
  s.amips_ref = 7.5;
  s.sj_ref = 0.2;
  s.power = power;
  return s;
}

// The definition, one point: (AMIPS / A0)^p + sum over corners of
// (sJ0 / sJ)^p, sJ = sqrt(2) det J / prod |K u_i| (J = K W).
double point_terms(const volume::DescentTerms& s, const Mat3& k, double& worst) {
  const double det = k.determinant();
  const double amips = k.squaredNorm() / std::cbrt(det * det);
  double e = std::pow(amips / s.amips_ref, s.power);
  worst = std::max(worst, amips / s.amips_ref);
  for (const auto& corner : highorder::AmipsFrames::kCornerEdges) {
    double lengths = 1;
    for (int i : corner) lengths *= (k * s.edges[i]).norm();
    const double sj = std::sqrt(2.0) * det * s.reference_det / lengths;
    e += std::pow(s.sj_ref / sj, s.power);
    worst = std::max(worst, s.sj_ref / sj);
  }
  return e;
}

std::vector<Mat3> random_frames(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  std::vector<Mat3> k(n);
  for (auto& f : k) {
    f = Mat3::Identity();
    for (int e = 0; e < 9; ++e) f.data()[e] += u(rng);
    if (f.determinant() < 0) f.col(0) *= -1;
  }
  return k;
}

} // namespace

TEST(DescentTerms, EqualTheirDefinitionAtEveryPoint) {
  for (int power : {2, 8, 16})
    for (int n : {1, 8, 13, 165}) { // whole and partial blocks
      SCOPED_TRACE(testing::Message() << "p " << power << ", " << n << " points");
      const auto s = terms(power);
      const auto k = random_frames(n, 7 * n + power);
      double expected_worst = 0, expected = 0;
      for (const Mat3& f : k) expected += point_terms(s, f, expected_worst);
      double worst = 0;
      std::vector<Mat3> dk(n);
      const double sum = s(k.data(), n, dk.data(), worst);
      EXPECT_NEAR(sum, expected, 1e-12 * expected);
      EXPECT_NEAR(worst, expected_worst, 1e-12 * expected_worst);
      double worst_without_gradient = 0;
      EXPECT_EQ(s(k.data(), n, nullptr, worst_without_gradient), sum);
      EXPECT_EQ(worst_without_gradient, worst);
    }
}

TEST(DescentTerms, GradientEqualsCentralDifferences) {
  const auto s = terms(8);
  const int n = 11;
  auto k = random_frames(n, 3);
  std::vector<Mat3> dk(n);
  double worst = 0;
  s(k.data(), n, dk.data(), worst);
  for (int q = 0; q < n; ++q)
    for (int e = 0; e < 9; ++e) {
      const double h = 1e-6, x = k[q].data()[e];
      double w = 0, one = 0, two = 0;
      k[q].data()[e] = x + h;
      one = point_terms(s, k[q], w);
      k[q].data()[e] = x - h;
      two = point_terms(s, k[q], w);
      k[q].data()[e] = x;
      const double numeric = (one - two) / (2 * h);
      EXPECT_NEAR(dk[q].data()[e], numeric, 1e-6 * (1 + std::abs(numeric))) << "point " << q << ", entry " << e;
    }
}

TEST(DescentTerms, InfiniteWhereAFrameIsNotPositive) {
  const auto s = terms(8);
  auto k = random_frames(12, 5);
  double worst = 0;
  EXPECT_TRUE(std::isfinite(s(k.data(), 12, nullptr, worst)));
  for (int q : {0, 9, 11}) { // first block, second block, last point
    auto flat = k;
    flat[q].col(2) = flat[q].col(0); // det = 0 exactly
    EXPECT_EQ(s(flat.data(), 12, nullptr, worst), std::numeric_limits<double>::infinity()) << q;
    flat[q].col(2) = -k[q].col(2); // det < 0
    EXPECT_EQ(s(flat.data(), 12, nullptr, worst), std::numeric_limits<double>::infinity()) << q;
  }
}

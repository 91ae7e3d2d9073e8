// The optimizer's AMIPS energy and gradient (volume/tet_amips.hpp) against
// the textbook formula tr(JᵀJ)/(3 det(J)^{2/3}), J = E W⁻¹, and against
// central differences.
#include "curvetet/volume/tet_amips.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace curvetet {
namespace {

using mesh::Vec3;

double reference_amips(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Eigen::Matrix3d w, e;
  w << 1, 0.5, 0.5, 0, std::sqrt(3.0) / 2, std::sqrt(3.0) / 6, 0, 0, std::sqrt(2.0 / 3.0);
  e << b - a, c - a, d - a;
  const Eigen::Matrix3d j = e * w.inverse();
  return j.squaredNorm() / (3 * std::pow(j.determinant(), 2.0 / 3.0));
}

TEST(TetAmips, RegularTetHasEnergyOneAtAnyScale) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.5, std::sqrt(3.0) / 2, 0), d(0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0));
  for (double s : {1e-7, 1.0, 3e5}) EXPECT_NEAR(volume::tet_amips(s * a, s * b, s * c, s * d), 1.0, 1e-12);
}

TEST(TetAmips, FlatAndInvertedTetsAreInfinite) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  EXPECT_TRUE(std::isinf(volume::tet_amips(a, b, c, Vec3(0.3, 0.3, 0))));
  EXPECT_TRUE(std::isinf(volume::tet_amips(a, c, b, d)));
  EXPECT_TRUE(std::isinf(volume::tet_amips_cubed(a, c, b, d)));
  Vec3 g;
  EXPECT_TRUE(std::isinf(volume::tet_amips_gradient(a, c, b, d, 0, g)));
}

TEST(TetAmips, MatchesTheReferenceAndItsGradientMatchesCentralDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int checked = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Vec3 x[4];
    const double scale = std::pow(10.0, 3 * u(rng)); // one scale per tet
    for (auto& p : x) p = scale * Vec3(u(rng), u(rng), u(rng));
    if (!((x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0])) > 0)) std::swap(x[1], x[2]);
    const double ref = reference_amips(x[0], x[1], x[2], x[3]);
    if (!(ref < 1e3)) continue; // near-flat: differences too noisy to compare
    EXPECT_NEAR(volume::tet_amips(x[0], x[1], x[2], x[3]), ref, 1e-9 * ref);
    EXPECT_NEAR(volume::tet_amips_cubed(x[0], x[1], x[2], x[3]), ref * ref * ref, 1e-9 * ref * ref * ref);
    for (int k = 0; k < 4; ++k) {
      Vec3 g;
      EXPECT_NEAR(volume::tet_amips_gradient(x[0], x[1], x[2], x[3], k, g), ref, 1e-9 * ref);
      const double h = 1e-6 * scale;
      Vec3 fd;
      for (int i = 0; i < 3; ++i) {
        Vec3 p[4] = {x[0], x[1], x[2], x[3]}, q[4] = {x[0], x[1], x[2], x[3]};
        p[k][i] += h;
        q[k][i] -= h;
        fd[i] = (reference_amips(p[0], p[1], p[2], p[3]) - reference_amips(q[0], q[1], q[2], q[3])) / (2 * h);
      }
      EXPECT_LE((g - fd).norm(), 1e-5 * (fd.norm() + ref / scale)) << trial << " corner " << k;
    }
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

// The bound is attained (apex above the centroid) and no apex beats it: a
// random search over apexes never goes below, and gets near it.
TEST(TetAmips, LeastEnergyOnAFaceIsAttainedAndNeverBeaten) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 a(u(rng), u(rng), 0), b(u(rng), u(rng), 0), c(u(rng), u(rng), 0);
    const double bound = volume::least_amips_on_face(a, b, c);
    const double l = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
    const double up = (b - a).cross(c - a).z() > 0 ? 1 : -1; // the side where the tet is positive
    const Vec3 best = (a + b + c) / 3 + Vec3(0, 0, up * std::sqrt(2 * l / 9));
    EXPECT_NEAR(reference_amips(a, b, c, best), bound, 1e-9 * bound);
    double least = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 2000; ++k) {
      const Vec3 apex = best + 0.3 * std::sqrt(l) * Vec3(u(rng), u(rng), u(rng));
      const double e = volume::tet_amips(a, b, c, apex);
      EXPECT_GE(e, bound * (1 - 1e-12));
      least = std::min(least, e);
    }
    EXPECT_LT(least, 1.05 * bound);
  }
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.5, std::sqrt(3.0) / 2, 0);
  EXPECT_NEAR(volume::least_amips_on_face(a, b, c), 1.0, 1e-12);
  EXPECT_TRUE(std::isinf(volume::least_amips_on_face(a, b, Vec3(2, 0, 0))));
}

} // namespace
} // namespace curvetet

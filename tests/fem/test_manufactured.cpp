// The paper's Franke solution: the analytic Laplacian (which becomes the
// source term f) agrees with finite differences of the value, also after
// bounding-box scaling.
#include "curvetet/fem/manufactured.hpp"

#include <gtest/gtest.h>

namespace curvetet::fem {
namespace {

double finite_difference_laplacian(const ManufacturedSolution& s, const Eigen::Vector3d& x, double h) {
  double lap = 0;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d e = Eigen::Vector3d::Unit(k) * h;
    lap += (s.value(x + e) - 2 * s.value(x) + s.value(x - e)) / (h * h);
  }
  return lap;
}

TEST(Franke, LaplacianMatchesFiniteDifferences) {
  ManufacturedSolution s = franke_solution();
  for (double a : {0.1, 0.3, 0.5, 0.8})
    for (double b : {0.05, 0.4, 0.9}) {
      Eigen::Vector3d x(a, b, 1 - a * b);
      double fd = finite_difference_laplacian(s, x, 1e-4);
      EXPECT_NEAR(s.laplacian(x), fd, 1e-4 * (1 + std::abs(fd))) << x.transpose();
    }
}

TEST(Franke, KnownValueAtOrigin) {
  // u(0) = 3/4 e^{-3} + 3/4 e^{-1/49 - 1/5} + 1/2 e^{-(49+9+25)/4} - 1/5 e^{-(16+49+25)}.
  double expected = 0.75 * std::exp(-3.0) + 0.75 * std::exp(-1.0 / 49 - 0.2) + 0.5 * std::exp(-83.0 / 4) -
                    0.2 * std::exp(-90.0);
  EXPECT_NEAR(franke_solution().value(Eigen::Vector3d::Zero()), expected, 1e-15);
}

TEST(Franke, BoxScalingIsAChangeOfVariables) {
  BoxScaling box{Eigen::Vector3d(-2, 1, 3), 5};
  ManufacturedSolution unit = franke_solution(), scaled = franke_solution(box);
  Eigen::Vector3d t(0.3, 0.6, 0.2);
  Eigen::Vector3d x = box.origin + box.scale * t;
  EXPECT_NEAR(scaled.value(x), unit.value(t), 1e-15);
  EXPECT_NEAR(scaled.laplacian(x), unit.laplacian(t) / 25, 1e-12 * std::abs(unit.laplacian(t)));
  double fd = finite_difference_laplacian(scaled, x, 1e-3);
  EXPECT_NEAR(scaled.laplacian(x), fd, 1e-4 * (1 + std::abs(fd)));
}

TEST(Franke, BoundingBoxOfTetNodesOnly) {
  mesh::TetMesh m;
  m.order = 1;
  m.nodes = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}, {100, 100, 100}}; // last node unused
  m.tets = {0, 1, 2, 3};
  BoxScaling box = tet_bounding_box(m);
  EXPECT_EQ(box.origin, Eigen::Vector3d::Zero());
  EXPECT_EQ(box.scale, 2);
}

} // namespace
} // namespace curvetet::fem

// Bases: partition of unity, interpolation (Kronecker delta at the nodes),
// exact Lagrange <-> Bernstein round trip, gradients against finite
// differences, degree elevation and de Casteljau bisection keep the polynomial.
#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/node_ordering.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace curvetet::highorder;

namespace {

std::vector<double> node_xi(int dim, int order, int i) {
  if (dim == 2) {
    auto p = triangle_node(order, i);
    return {double(p[0]) / order, double(p[1]) / order};
  }
  auto p = tet_node(order, i);
  return {double(p[0]) / order, double(p[1]) / order, double(p[2]) / order};
}

std::vector<double> random_xi(int dim, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> x(dim);
  double s;
  do {
    s = 0;
    for (auto& v : x) s += (v = u(rng));
  } while (s > 1);
  return x;
}

int node_count(int dim, int order) { return dim == 2 ? triangle_node_count(order) : tet_node_count(order); }

} // namespace

class EveryOrder : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(EveryOrder, PartitionOfUnityAndInterpolation) {
  auto [dim, order] = GetParam();
  const int n = node_count(dim, order);
  for (int i = 0; i < n; ++i) {
    auto xi = node_xi(dim, order, i);
    Eigen::VectorXd l = lagrange_basis(dim, order, xi.data());
    for (int j = 0; j < n; ++j) EXPECT_NEAR(l[j], i == j ? 1.0 : 0.0, 1e-11) << "node " << i << " basis " << j;
  }
  std::mt19937 rng(7);
  for (int k = 0; k < 20; ++k) {
    auto xi = random_xi(dim, rng);
    EXPECT_NEAR(lagrange_basis(dim, order, xi.data()).sum(), 1.0, 1e-12);
    Eigen::MatrixXd g = lagrange_gradients(dim, order, xi.data());
    for (int c = 0; c < dim; ++c) EXPECT_NEAR(g.col(c).sum(), 0.0, 1e-10);
  }
}

TEST_P(EveryOrder, LagrangeBernsteinRoundTrip) {
  auto [dim, order] = GetParam();
  const auto& bc = basis_change(dim, order);
  const int n = node_count(dim, order);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd f(n);
  for (int i = 0; i < n; ++i) f[i] = u(rng);
  Eigen::VectorXd back = bc.bernstein_to_lagrange * (bc.lagrange_to_bernstein * f);
  EXPECT_LT((back - f).cwiseAbs().maxCoeff(), 1e-12);
  // The Bernstein form evaluates to the same values as the Lagrange form.
  Eigen::VectorXd b = bc.lagrange_to_bernstein * f;
  std::vector<double> bv(b.data(), b.data() + n);
  for (int k = 0; k < 10; ++k) {
    auto xi = random_xi(dim, rng);
    std::vector<double> lambda{1.0};
    for (double x : xi) {
      lambda.push_back(x);
      lambda[0] -= x;
    }
    EXPECT_NEAR(bernstein_eval(dim, order, bv.data(), lambda.data()), lagrange_basis(dim, order, xi.data()).dot(f),
                1e-11);
  }
}

TEST_P(EveryOrder, GradientsMatchFiniteDifferences) {
  auto [dim, order] = GetParam();
  std::mt19937 rng(11);
  for (int k = 0; k < 5; ++k) {
    auto xi = random_xi(dim, rng);
    for (auto& x : xi) x = 0.05 + 0.5 * x; // stay inside for the central differences
    Eigen::MatrixXd g = lagrange_gradients(dim, order, xi.data());
    for (int c = 0; c < dim; ++c) {
      const double h = 1e-6;
      auto xp = xi, xm = xi;
      xp[c] += h;
      xm[c] -= h;
      Eigen::VectorXd fd = (lagrange_basis(dim, order, xp.data()) - lagrange_basis(dim, order, xm.data())) / (2 * h);
      EXPECT_LT((fd - g.col(c)).cwiseAbs().maxCoeff(), 1e-5 * (1 + g.col(c).cwiseAbs().maxCoeff()));
    }
  }
}

TEST_P(EveryOrder, ElevationDerivativeAndBisectionKeepThePolynomial) {
  auto [dim, order] = GetParam();
  const int n = lattice_size(dim, order);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> c(n);
  for (auto& v : c) v = u(rng);
  auto up = degree_elevate(dim, order, c);
  auto [left, right] = bisect(dim, order, c, 0, 1);
  for (int k = 0; k < 10; ++k) {
    auto xi = random_xi(dim, rng);
    std::vector<double> lambda{1.0};
    for (double x : xi) {
      lambda.push_back(x);
      lambda[0] -= x;
    }
    const double f = bernstein_eval(dim, order, c.data(), lambda.data());
    EXPECT_NEAR(bernstein_eval(dim, order + 1, up.data(), lambda.data()), f, 1e-12);
    // Left child: vertices (v0, m01, v2[, v3]); child barycentric mu maps to
    // parent lambda = (mu0 + mu1/2, mu1/2, mu2, mu3).
    std::vector<double> parent = lambda;
    parent[0] = lambda[0] + 0.5 * lambda[1];
    parent[1] = 0.5 * lambda[1];
    EXPECT_NEAR(bernstein_eval(dim, order, left.data(), lambda.data()),
                bernstein_eval(dim, order, c.data(), parent.data()), 1e-12);
    parent = lambda;
    parent[1] = lambda[1] + 0.5 * lambda[0];
    parent[0] = 0.5 * lambda[0];
    EXPECT_NEAR(bernstein_eval(dim, order, right.data(), lambda.data()),
                bernstein_eval(dim, order, c.data(), parent.data()), 1e-12);
    // Derivative coefficients match finite differences of the polynomial.
    auto d1 = bernstein_derivative(dim, order, c, 1);
    const double h = 1e-6;
    auto lp = lambda, lm = lambda;
    lp[1] += h, lp[0] -= h, lm[1] -= h, lm[0] += h;
    const double fd =
        (bernstein_eval(dim, order, c.data(), lp.data()) - bernstein_eval(dim, order, c.data(), lm.data())) / (2 * h);
    EXPECT_NEAR(order == 0 ? 0 : bernstein_eval(dim, order - 1, d1.data(), lambda.data()), fd, 1e-6 * (1 + std::abs(fd)));
  }
}

INSTANTIATE_TEST_SUITE_P(TrianglesAndTets, EveryOrder,
                         ::testing::Combine(::testing::Values(2, 3), ::testing::Range(1, kMaxOrder + 1)));

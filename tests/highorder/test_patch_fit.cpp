#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/patch_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace curvetet::highorder;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

// A hexagonal fan of 6 triangles around corner 0, in the (s, t) plane:
//        2 --- 1
//       / \   / \ .
//      3 --  0 -- 6      corners 1..6 on the unit circle
//       \ /   \ /
//        4 --- 5
struct Fan {
  std::vector<Vector2d> params;
  std::vector<std::array<int, 3>> triangles;
};

Fan hexagonal_fan() {
  Fan f;
  f.params.push_back(Vector2d(0, 0));
  for (int i = 0; i < 6; ++i) f.params.push_back(Vector2d(std::cos(M_PI / 3 * i), std::sin(M_PI / 3 * i)));
  for (int i = 0; i < 6; ++i) f.triangles.push_back({0, 1 + i, 1 + (i + 1) % 6});
  return f;
}

// Height field of total degree k (exactly representable by degree-k triangles
// since each triangle's parametrization is affine).
Vector3d surface(const Vector2d& st, int k) {
  double z = 0.3;
  for (int a = 0; a <= k; ++a)
    for (int b = 0; a + b <= k; ++b) z += 0.1 * (1 + a - b) * std::pow(st.x(), a) * std::pow(st.y(), b);
  return Vector3d(st.x(), st.y(), z);
}

PatchFitProblem problem_on(const Fan& fan, int k, int samples_per_triangle, bool fix_boundary) {
  PatchFitProblem p;
  p.degree = k;
  p.triangles = fan.triangles;
  for (const auto& st : fan.params) p.corners.push_back(surface(st, k));
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u01(0, 1);
  for (int t = 0; t < 6; ++t) {
    const auto& tri = fan.triangles[t];
    for (int s = 0; s < samples_per_triangle; ++s) {
      double u = u01(rng), v = u01(rng);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      Vector2d st = (1 - u - v) * fan.params[tri[0]] + u * fan.params[tri[1]] + v * fan.params[tri[2]];
      p.samples.push_back({t, Vector2d(u, v), surface(st, k)});
    }
    if (fix_boundary) { // outer edge (tri[1], tri[2])
      PatchFitProblem::FixedEdge e{tri[1], tri[2], {}};
      for (int j = 1; j < k; ++j)
        e.nodes.push_back(surface(fan.params[tri[1]] + (fan.params[tri[2]] - fan.params[tri[1]]) * (double(j) / k), k));
      p.fixed_edges.push_back(e);
    }
  }
  return p;
}

} // namespace

TEST(PatchFit, ReproducesAPolynomialSurfaceOfTheFittedDegree) {
  const Fan fan = hexagonal_fan();
  for (int k = 1; k <= 5; ++k)
    for (bool fix : {false, true}) {
      auto p = problem_on(fan, k, 40, fix);
      auto fit = fit_patch_star(p);
      EXPECT_LT(fit.max_residual, 1e-10) << "k=" << k << " fixed=" << fix;
      // Nodes sit exactly on the surface at their lattice positions.
      for (int t = 0; t < 6; ++t) {
        const auto& tri = fan.triangles[t];
        for (int i = 0; i < triangle_node_count(k); ++i) {
          auto n = triangle_node(k, i);
          double u = double(n[0]) / k, v = double(n[1]) / k;
          Vector2d st = (1 - u - v) * fan.params[tri[0]] + u * fan.params[tri[1]] + v * fan.params[tri[2]];
          EXPECT_LT((fit.nodes[t][i] - surface(st, k)).norm(), 1e-10) << "k=" << k << " t=" << t << " i=" << i;
        }
      }
    }
}

TEST(PatchFit, SharedEdgesGetOneNodeAndUnconstrainedNodesStayFlat) {
  const Fan fan = hexagonal_fan();
  auto p = problem_on(fan, 3, 0, false); // no samples at all
  auto fit = fit_patch_star(p);
  // 6 interior edges x 2 + 6 outer edges x 2 + 6 faces x 1 free nodes.
  EXPECT_EQ(fit.free_nodes, 30);
  // Without samples every node is on its flat triangle.
  for (int t = 0; t < 6; ++t) {
    const auto& tri = fan.triangles[t];
    for (int i = 0; i < triangle_node_count(3); ++i) {
      auto n = triangle_node(3, i);
      Vector3d flat = ((3 - n[0] - n[1]) * p.corners[tri[0]] + n[0] * p.corners[tri[1]] + n[1] * p.corners[tri[2]]) / 3.0;
      EXPECT_LT((fit.nodes[t][i] - flat).norm(), 1e-14);
    }
  }
  // Neighbouring triangles agree on their shared edge (0, tri[2]) nodes.
  auto fitted = fit_patch_star(problem_on(fan, 3, 30, false));
  // triangle t edge (0 -> corner2) is triangle t+1 edge (0 -> corner1): in
  // internal order edge 2-0 nodes are indices 7, 8 (from 2 to 0) and edge 0-1
  // nodes are 3, 4 (from 0 to 1).
  for (int t = 0; t < 6; ++t) {
    const auto& a = fitted.nodes[t];
    const auto& b = fitted.nodes[(t + 1) % 6];
    EXPECT_EQ(a[7], b[4]);
    EXPECT_EQ(a[8], b[3]);
  }
}

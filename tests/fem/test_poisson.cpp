// Poisson solver on Gmsh meshes: dof placement, exactness for a quadratic
// solution on straight meshes (any geometry order), convergence rates on a
// cube, the benefit of curved geometry on a ball, and the CLI.
#include "curvetet/core/error.hpp"
#include "curvetet/fem/manufactured.hpp"
#include "curvetet/fem/poisson.hpp"
#include "gmsh_meshes.hpp"
#include "support/run_command.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace curvetet::fem {
namespace {

#define REQUIRE_GMSH()                                                                                               \
  if (!test::python_gmsh_available()) GTEST_SKIP() << "python3-gmsh not importable by /usr/bin/python3"

// u = x^2 + 2y^2 - z^2 + xy - 2yz + 3x - y + 1, Δu = 4.
ManufacturedSolution quadratic_solution() {
  return {[](const Eigen::Vector3d& p) {
            double x = p.x(), y = p.y(), z = p.z();
            return x * x + 2 * y * y - z * z + x * y - 2 * y * z + 3 * x - y + 1;
          },
          [](const Eigen::Vector3d&) { return 4.0; }};
}

struct SolveFigures {
  double error, relative, h;
  int dofs;
};

SolveFigures solve(const mesh::TetMesh& m, const ManufacturedSolution& exact, int degree) {
  PoissonOptions options;
  options.degree = degree;
  PoissonResult r = solve_poisson(m, manufactured_problem(exact), options);
  L2Norms n = l2_error(m, r.solution, exact.value);
  return {n.error, n.error / n.exact, std::cbrt(n.volume / m.num_tets()), r.solution.num_dofs()};
}

TEST(Poisson, DofsOfOrderPSitOnTheGeometryNodes) {
  REQUIRE_GMSH();
  mesh::TetMesh m = test::gmsh_mesh("ball", 0.5, 2);
  FiniteElementField f = make_field(m, 2);
  ASSERT_EQ(f.dofs_per_tet, m.tet_nodes());
  for (int t = 0; t < m.num_tets(); ++t)
    for (int j = 0; j < f.dofs_per_tet; ++j)
      ASSERT_LT((f.dof_positions[f.tet_dofs[t * f.dofs_per_tet + j]] - m.nodes[m.tet(t)[j]]).norm(), 1e-14)
          << "tet " << t << " node " << j;
  // Conforming: as many dofs as distinct geometry nodes used by tets.
  std::vector<char> used(m.nodes.size(), 0);
  for (int id : m.tets) used[id] = 1;
  EXPECT_EQ(f.num_dofs(), std::count(used.begin(), used.end(), 1));
}

TEST(Poisson, QuadraticSolutionIsExactOnStraightMeshes) {
  REQUIRE_GMSH();
  for (int order : {1, 2, 3}) { // the cube's high-order nodes are placed affinely
    mesh::TetMesh m = test::gmsh_mesh("cube", order == 3 ? 0.5 : 0.35, order);
    ManufacturedSolution exact = quadratic_solution();
    PoissonResult r = solve_poisson(m, manufactured_problem(exact), {});
    double max_nodal = 0;
    for (int d = 0; d < r.solution.num_dofs(); ++d)
      max_nodal = std::max(max_nodal, std::abs(r.solution.values[d] - exact.value(r.solution.dof_positions[d])));
    L2Norms n = l2_error(m, r.solution, exact.value);
    EXPECT_LT(n.error / n.exact, 1e-10) << "P = " << order;
    EXPECT_LT(max_nodal, 1e-9) << "P = " << order;
    EXPECT_NEAR(n.volume, 1.0, 1e-12) << "P = " << order;
    EXPECT_GT(r.num_dirichlet, 0);
  }
}

TEST(Poisson, QuadraticSolutionIsNotExactWithLinearUnknowns) {
  REQUIRE_GMSH();
  mesh::TetMesh m = test::gmsh_mesh("cube", 0.35, 1);
  EXPECT_GT(solve(m, quadratic_solution(), 1).relative, 1e-4); // the exactness test above can fail
}

TEST(Poisson, ConvergesAtRateQPlusOneOnACube) {
  REQUIRE_GMSH();
  ManufacturedSolution exact = franke_solution(); // the cube is [0,1]^3: no scaling
  mesh::TetMesh coarse = test::gmsh_mesh("cube", 0.2, 1), fine = test::gmsh_mesh("cube", 0.1, 1);
  for (int degree : {1, 2}) {
    SolveFigures a = solve(coarse, exact, degree), b = solve(fine, exact, degree);
    double rate = std::log(a.error / b.error) / std::log(a.h / b.h);
    std::printf("Q = %d: h %.4f -> %.4f, L2 %.4e -> %.4e, rate %.2f\n", degree, a.h, b.h, a.error, b.error, rate);
    // Measured 1.65 (Q = 1, still pre-asymptotic on the Franke bumps) and 3.04 (Q = 2).
    EXPECT_GT(rate, degree == 1 ? 1.5 : 2.7) << "Q = " << degree;
    EXPECT_LT(b.error, a.error);
  }
}

// -Δu = 1 in the unit ball, u = 0 on the sphere: u = (1 - |x|^2) / 6. The
// data live on the true boundary, so the error of a straight (P = 1) mesh is
// dominated by the domain approximation; order-2 geometry removes most of it.
TEST(Poisson, CurvedBallGeometryBeatsStraightGeometry) {
  REQUIRE_GMSH();
  PoissonProblem problem{[](const Eigen::Vector3d&) { return 1.0; }, [](const Eigen::Vector3d&) { return 0.0; }};
  auto exact = [](const Eigen::Vector3d& x) { return (1 - x.squaredNorm()) / 6; };
  double errors[2];
  for (int order : {1, 2}) {
    mesh::TetMesh m = test::gmsh_mesh("ball", 0.3, order);
    PoissonResult r = solve_poisson(m, problem, {});
    errors[order - 1] = l2_error(m, r.solution, exact).error;
  }
  std::printf("ball h = 0.3, Q = 2: L2 error straight %.4e, curved %.4e\n", errors[0], errors[1]);
  EXPECT_LT(errors[1], 0.1 * errors[0]); // measured 1.2e-4 vs 7.3e-3
}

TEST(Poisson, ConjugateGradientsAgreeWithTheDirectSolver) {
  REQUIRE_GMSH();
  mesh::TetMesh m = test::gmsh_mesh("ball", 0.5, 2);
  ManufacturedSolution exact = franke_solution(tet_bounding_box(m));
  PoissonOptions options;
  options.solver = LinearSolver::direct;
  PoissonResult direct = solve_poisson(m, manufactured_problem(exact), options);
  options.solver = LinearSolver::conjugate_gradient;
  PoissonResult cg = solve_poisson(m, manufactured_problem(exact), options);
  EXPECT_EQ(direct.solver_used, LinearSolver::direct);
  EXPECT_EQ(cg.solver_used, LinearSolver::conjugate_gradient);
  EXPECT_GT(cg.cg_iterations, 0);
  EXPECT_LT((cg.solution.values - direct.solution.values).lpNorm<Eigen::Infinity>(),
            1e-9 * direct.solution.values.lpNorm<Eigen::Infinity>());
}

TEST(Poisson, RejectsInvalidDegree) {
  mesh::TetMesh m;
  m.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.tets = {0, 1, 2, 3};
  PoissonOptions options;
  options.degree = 9;
  EXPECT_THROW(solve_poisson(m, manufactured_problem(quadratic_solution()), options), Error);
}

TEST(Poisson, RejectsInvertedTet) {
  mesh::TetMesh m;
  m.nodes = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}}; // negative orientation
  m.tets = {0, 1, 2, 3};
  EXPECT_THROW(solve_poisson(m, manufactured_problem(quadratic_solution()), {}), Error);
}

TEST(PoissonCommand, ReportsTheLibraryFigures) {
  REQUIRE_GMSH();
  std::string path = test::gmsh_mesh_path("ball", 0.5, 2);
  auto r = test::run_command(std::string(CURVETET_BINARY) + " poisson " + test::quoted(path) + " --degree 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  auto j = nlohmann::json::parse(r.out)["poisson"];
  mesh::TetMesh m = io::read_msh(path);
  ManufacturedSolution exact = franke_solution(tet_bounding_box(m));
  SolveFigures run = solve(m, exact, 2);
  EXPECT_EQ(j["dofs"].get<int>(), run.dofs);
  EXPECT_EQ(j["geometry_order"].get<int>(), 2);
  EXPECT_NEAR(j["l2_error"].get<double>(), run.error, 1e-12 * run.error);
  EXPECT_NEAR(j["l2_relative_error"].get<double>(), run.relative, 1e-12 * run.relative);
}

} // namespace
} // namespace curvetet::fem

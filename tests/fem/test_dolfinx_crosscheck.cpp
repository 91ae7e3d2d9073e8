// Cross-check against DOLFINx 0.5 (python3-dolfinx): same order-2 curved
// ball, same problem (paper's Franke solution scaled to the bounding box),
// P2 unknowns; the L2 errors must agree within 1 %. Also on the straight
// order-1 ball (subparametric P2).
#include "curvetet/fem/manufactured.hpp"
#include "curvetet/fem/poisson.hpp"
#include "gmsh_meshes.hpp"
#include "support/run_command.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace curvetet::fem {
namespace {

bool dolfinx_available() {
  return std::system("/usr/bin/python3 -c 'import dolfinx, dolfinx.fem.petsc, gmsh' > /dev/null 2>&1") == 0;
}

nlohmann::json run_dolfinx(const std::string& mesh_path, int degree) {
  auto r = test::run_command(fmt::format("/usr/bin/python3 '{}/tests/fem/dolfinx_poisson.py' '{}' {} 2>/dev/null",
                                         CURVETET_SOURCE_DIR, mesh_path, degree));
  EXPECT_EQ(r.exit_code, 0) << r.out;
  auto last_line = r.out.substr(r.out.rfind('{'));
  return nlohmann::json::parse(last_line);
}

TEST(DolfinxCrossCheck, SameL2ErrorOnCurvedOrder2Ball) {
  if (!dolfinx_available()) GTEST_SKIP() << "dolfinx (python3-dolfinx) not importable by /usr/bin/python3";
  if (!test::python_gmsh_available()) GTEST_SKIP() << "python3-gmsh not importable";
  for (int order : {2, 1}) {
    std::string path = test::gmsh_mesh_path("ball", 0.3, order);
    mesh::TetMesh m = io::read_msh(path);
    ManufacturedSolution exact = franke_solution(tet_bounding_box(m));
    PoissonResult r = solve_poisson(m, manufactured_problem(exact), {});
    L2Norms ours = l2_error(m, r.solution, exact.value);
    nlohmann::json theirs = run_dolfinx(path, 2);
    std::printf("P = %d: curvetet L2 %.6e (%d dofs), DOLFINx L2 %.6e (%d dofs)\n", order, ours.error,
                r.solution.num_dofs(), theirs["l2_error"].get<double>(), theirs["dofs"].get<int>());
    EXPECT_EQ(theirs["geometry_order"].get<int>(), order);
    EXPECT_EQ(theirs["dofs"].get<int>(), r.solution.num_dofs());
    EXPECT_NEAR(theirs["l2_exact"].get<double>(), ours.exact, 1e-6 * ours.exact);
    // Measured: relative difference 5e-6 (P = 2) and 2e-4 (P = 1).
    EXPECT_NEAR(theirs["l2_error"].get<double>(), ours.error, 0.01 * ours.error) << "P = " << order;
  }
}

} // namespace
} // namespace curvetet::fem

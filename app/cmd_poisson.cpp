// `curvetet poisson MESH.msh [--degree Q] [--json]`: the paper's §6.4
// "Large scale Poisson" example. Solves -Δu = f on the curved tet mesh with
// order-Q unknowns on the mesh's order-P geometry (fem/poisson.hpp), u = the
// Franke solution scaled to the mesh's bounding box (fem/manufactured.hpp),
// g = u on the boundary, and prints the dofs and the L2 error.
#include "commands.hpp"

#include "curvetet/core/report.hpp"
#include "curvetet/fem/manufactured.hpp"
#include "curvetet/fem/poisson.hpp"
#include "curvetet/io/msh.hpp"

#include <chrono>
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace curvetet::app {

Command add_poisson_command(CLI::App& root) {
  struct Options {
    std::string mesh_path;
    int degree = 2;
    int quadrature_degree = 0;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("poisson", "Solve the paper's Poisson example on a curved tet mesh, report the L2 error");
  cmd->add_option("MESH", o->mesh_path, "Curved tet mesh, Gmsh MSH 4.1 or 2.2")->required()->check(CLI::ExistingFile);
  cmd->add_option("--degree", o->degree, "Order Q of the Lagrange unknowns")->check(CLI::Range(1, 8))->capture_default_str();
  cmd->add_option("--quadrature-degree", o->quadrature_degree, "Quadrature degree (0 = automatic)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--json", o->json, "Print the report as JSON on stdout");
  return {cmd, [o]() {
            Report report;
            mesh::TetMesh mesh;
            {
              StageTimer t(&report, "read mesh");
              mesh = io::read_msh(o->mesh_path);
            }
            auto start = std::chrono::steady_clock::now();
            fem::BoxScaling box = fem::tet_bounding_box(mesh);
            fem::ManufacturedSolution exact = fem::franke_solution(box);
            fem::PoissonOptions options;
            options.degree = o->degree;
            options.quadrature_degree = o->quadrature_degree;
            fem::PoissonResult result;
            {
              StageTimer t(&report, "solve");
              result = fem::solve_poisson(mesh, fem::manufactured_problem(exact), options);
            }
            fem::L2Norms norms;
            {
              StageTimer t(&report, "l2 error");
              norms = fem::l2_error(mesh, result.solution, exact.value);
            }
            double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            auto& j = report["poisson"];
            j["path"] = o->mesh_path;
            j["tets"] = mesh.num_tets();
            j["geometry_order"] = mesh.order;
            j["degree"] = result.solution.degree;
            j["dofs"] = result.solution.num_dofs();
            j["dirichlet_dofs"] = result.num_dirichlet;
            j["quadrature_degree"] = result.quadrature_degree;
            j["solver"] = result.solver_used == fem::LinearSolver::direct ? "SimplicialLDLT" : "CG+IncompleteCholesky";
            j["cg_iterations"] = result.cg_iterations;
            j["volume"] = norms.volume;
            j["l2_error"] = norms.error;
            j["l2_relative_error"] = norms.error / norms.exact;
            j["seconds"] = seconds;
            if (o->json)
              std::cout << report.json().dump(2) << '\n';
            else
              std::cout << fmt::format("{}: {} tets (P = {}), Q = {}: {} dofs ({} Dirichlet), L2 error {:.6e} "
                                       "(relative {:.6e}), {:.3f} s\n",
                                       o->mesh_path, mesh.num_tets(), mesh.order, result.solution.degree,
                                       result.solution.num_dofs(), result.num_dirichlet, norms.error,
                                       norms.error / norms.exact, seconds);
            return 0;
          }};
}

} // namespace curvetet::app

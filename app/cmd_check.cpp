// `curvetet check MESH.msh [--input SURFACE] [--epsilon E] [--json] [--vtu OUT]`:
// re-verifies a curved tet mesh from the file alone (check/verify_tet_mesh.hpp):
// certified positivity of every tet, conformity, a closed manifold
// intersection-free boundary, and with --input the distances to the input.
// Exit code 0 when every check passes, ExitCode::verification otherwise.
#include "commands.hpp"

#include "curvetet/check/verify_tet_mesh.hpp"
#include "curvetet/core/error.hpp"
#include "curvetet/core/report.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/io/vtu.hpp"

#include <iostream>
#include <memory>

namespace curvetet::app {

Command add_check_command(CLI::App& root) {
  struct Options {
    std::string mesh_path, input_path, vtu_path;
    double epsilon = 1e-2;
    int segments = 0;
    int max_depth = highorder::CertificateOptions{}.max_depth;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("check", "Re-verify a curved tet mesh (.msh): positivity, boundary, distance");
  cmd->add_option("MESH", o->mesh_path, "Curved tet mesh, Gmsh MSH 4.1 or 2.2")->required()->check(CLI::ExistingFile);
  cmd->add_option("--input", o->input_path, "Input surface the mesh approximates (.off/.obj/.stl/.ply)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--epsilon", o->epsilon, "Allowed distance between input and boundary, both ways (Hausdorff), relative to the input bbox diagonal")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--segments-per-edge", o->segments,
                  "Boundary linearization for the self-intersection test (0 = 2 x order)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-depth", o->max_depth, "Certificate subdivision depth (bisections)")
      ->check(CLI::Range(0, 60))
      ->capture_default_str();
  cmd->add_option("--vtu", o->vtu_path, "Also write the mesh as VTU with per-tet validity and quality fields");
  cmd->add_flag("--json", o->json, "Print the report as JSON on stdout");
  return {cmd, [o]() {
            Report report;
            mesh::TetMesh mesh;
            {
              StageTimer t(&report, "read mesh");
              mesh = io::read_msh(o->mesh_path);
            }
            mesh::SurfaceMesh input;
            check::TetMeshVerifyOptions vo;
            vo.epsilon = o->epsilon;
            vo.segments_per_edge = o->segments;
            vo.certificate.max_depth = o->max_depth;
            if (!o->input_path.empty()) {
              StageTimer t(&report, "read input");
              input = mesh::to_surface_mesh(io::read_surface(o->input_path));
              vo.input = &input;
            }
            check::TetMeshVerification v;
            {
              StageTimer t(&report, "verify");
              v = check::verify_tet_mesh(mesh, vo);
            }
            if (!o->vtu_path.empty()) {
              std::vector<double> validity(v.validity.size());
              for (std::size_t i = 0; i < validity.size(); ++i)
                validity[i] = v.validity[i] == highorder::Validity::positive ? 1 : (v.validity[i] == highorder::Validity::invalid ? -1 : 0);
              io::write_vtu(o->vtu_path, mesh,
                            {{"validity", validity},
                             {"min_det_lower_bound", v.min_det_lower},
                             {"min_scaled_jacobian", v.min_scaled_jacobian},
                             {"max_amips", v.max_amips}});
            }
            report["check"] = v.json();
            report["check"]["path"] = o->mesh_path;
            if (o->json)
              std::cout << report.json().dump(2) << '\n';
            else
              std::cout << o->mesh_path << ": " << v.text();
            return v.ok() ? 0 : static_cast<int>(ExitCode::verification);
          }};
}

} // namespace curvetet::app

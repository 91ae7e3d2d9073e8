// `curvetet deform MAP -o DEFORMED [--twist DEG | --displacement FILE]`: the
// paper's §6.4 "fast animation" example. A displacement of the coarse
// boundary nodes (a prescribed smooth twist, or a table with columns
// ux, uy, uz per boundary node, e.g. from `curvetet transfer` or a solver)
// is carried to the dense input through the map (map/deform.hpp); the
// deformed input surface is written (OFF/OBJ/STL/PLY), and with
// --coarse-output the deformed boundary too. For the twist the report gives
// how far the carried dense surface is from twisting the input directly.
#include "commands.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/core/report.hpp"
#include "curvetet/io/map_file.hpp"
#include "curvetet/io/vertex_table.hpp"
#include "curvetet/io/write_surface.hpp"
#include "curvetet/map/deform.hpp"
#include "curvetet/map/lattice_mesh.hpp"

#include <algorithm>
#include <iostream>
#include <memory>
#include <numbers>

namespace curvetet::app {

Command add_deform_command(CLI::App& root) {
  struct Options {
    std::string map_path, out_path, coarse_out, displacement_path, report_path;
    double twist_degrees = 90;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("deform", "Deform the coarse boundary and carry the motion to the dense input (paper §6.4)");
  cmd->add_option("MAP", o->map_path, "Map file written by `curvetet MESH --map`")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->out_path, "Deformed input surface (.off/.obj/.stl/.ply)")->required();
  auto* twist = cmd->add_option("--twist", o->twist_degrees, "Total twist about the longest bbox axis, degrees")
                    ->capture_default_str();
  cmd->add_option("--displacement", o->displacement_path,
                  "Boundary-node displacements (.csv/.ply with columns ux, uy, uz, one row per boundary node)")
      ->check(CLI::ExistingFile)
      ->excludes(twist);
  cmd->add_option("--coarse-output", o->coarse_out, "Also write the deformed coarse boundary (lattice triangles)");
  cmd->add_option("--report", o->report_path, "Write a JSON report to FILE");
  return {cmd, [o]() {
            Report report;
            const auto bmap = io::read_map(o->map_path);
            std::vector<mesh::Vec3> node_u(bmap.nodes.size());
            std::optional<map::Twist> twist;
            if (!o->displacement_path.empty()) {
              const auto table = io::read_vertex_table(o->displacement_path);
              int col[3];
              for (int d = 0; d < 3; ++d) {
                const std::string name = std::string("u") + char('x' + d);
                const auto it = std::find(table.names.begin(), table.names.end(), name);
                if (it == table.names.end()) throw Error(ExitCode::usage, o->displacement_path + ": no column " + name);
                col[d] = static_cast<int>(it - table.names.begin());
              }
              if (static_cast<std::size_t>(table.values.rows()) != node_u.size())
                throw Error(ExitCode::usage, o->displacement_path + ": one row per boundary node expected");
              for (std::size_t j = 0; j < node_u.size(); ++j)
                node_u[j] = mesh::Vec3(table.values(j, col[0]), table.values(j, col[1]), table.values(j, col[2]));
            } else {
              twist = map::twist_for(bmap.nodes, o->twist_degrees * std::numbers::pi / 180);
              for (std::size_t j = 0; j < node_u.size(); ++j) node_u[j] = map::displacement(*twist, bmap.nodes[j]);
            }
            mesh::SurfaceMesh deformed{map::carry_to_input(bmap, node_u), bmap.input.faces};
            io::write_surface(o->out_path, deformed);
            report["deform"] = {{"input_vertices", deformed.vertices.size()}, {"boundary_nodes", node_u.size()}};
            if (twist) {
              // The carried motion against the exact twist applied to the dense input.
              double worst = 0;
              for (std::size_t i = 0; i < deformed.vertices.size(); ++i) {
                const auto& x = bmap.input.vertices[i];
                worst = std::max(worst, (deformed.vertices[i] - (x + map::displacement(*twist, x))).norm());
              }
              const double diagonal = mesh::bbox_diagonal(bmap.input.vertices);
              report["deform"]["twist_degrees"] = o->twist_degrees;
              report["deform"]["max_deviation_from_exact_twist_relative"] = worst / diagonal;
              logger().info("twist {} deg: carried surface within {:.3g} x bbox diagonal of the exact twist",
                            o->twist_degrees, worst / diagonal);
            }
            if (!o->coarse_out.empty()) {
              auto coarse = map::boundary_lattice_mesh(bmap);
              for (std::size_t j = 0; j < node_u.size(); ++j) coarse.vertices[j] += node_u[j];
              io::write_surface(o->coarse_out, coarse);
            }
            if (!o->report_path.empty()) report.write(o->report_path);
            logger().info("wrote the deformed input ({} vertices) to {}", deformed.vertices.size(), o->out_path);
            return 0;
          }};
}

} // namespace curvetet::app

// `curvetet transfer MAP IN -o OUT --to boundary|input [--labels a,b]`: moves
// per-vertex attributes through the bijective map (map/transfer.hpp), from
// the input vertices to the output boundary nodes or back. IN and OUT are CSV
// or PLY vertex tables (io/vertex_table.hpp); OUT carries the positions of
// the side it lives on (and its faces for PLY: the input faces, or the
// boundary's lattice sub-triangles).
#include "commands.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/io/map_file.hpp"
#include "curvetet/io/vertex_table.hpp"
#include "curvetet/map/lattice_mesh.hpp"
#include "curvetet/map/transfer.hpp"

#include <memory>

namespace curvetet::app {

Command add_transfer_command(CLI::App& root) {
  struct Options {
    std::string map_path, in_path, out_path, to;
    std::vector<std::string> labels;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("transfer", "Move per-vertex attributes through the map (input <-> output boundary)");
  cmd->add_option("MAP", o->map_path, "Map file written by `curvetet MESH --map`")->required()->check(CLI::ExistingFile);
  cmd->add_option("IN", o->in_path, "Attributes (.csv or .ply) on the side the transfer starts from")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->out_path, "Transferred attributes (.csv or .ply)")->required();
  cmd->add_option("--to", o->to, "Where the attributes go: 'boundary' (from input vertices) or 'input' (from boundary nodes)")
      ->required()
      ->check(CLI::IsMember({"boundary", "input"}));
  cmd->add_option("--labels", o->labels, "Columns holding labels (nearest-label rule); default: a column named 'label'")
      ->delimiter(',');
  return {cmd, [o]() {
            const auto bmap = io::read_map(o->map_path);
            auto labels = o->labels;
            auto table = io::read_vertex_table(o->in_path, labels);
            if (labels.empty())
              for (std::size_t c = 0; c < table.names.size(); ++c) table.is_label[c] = table.names[c] == "label";
            const bool to_boundary = o->to == "boundary";
            io::VertexTable out;
            out.names = table.names;
            out.is_label = table.is_label;
            std::vector<mesh::Tri> faces;
            if (to_boundary) {
              out.values = map::input_to_boundary(bmap, table.values, table.is_label);
              out.positions = bmap.nodes;
              faces = map::boundary_lattice_mesh(bmap).faces;
            } else {
              out.values = map::boundary_to_input(bmap, table.values, table.is_label);
              out.positions = bmap.input.vertices;
              faces = bmap.input.faces;
            }
            io::write_vertex_table(o->out_path, out, faces);
            logger().info("transferred {} attribute column(s) from {} {} to {} {}; wrote {}", out.names.size(),
                          table.values.rows(), to_boundary ? "input vertices" : "boundary nodes", out.values.rows(),
                          to_boundary ? "boundary nodes" : "input vertices", o->out_path);
            return 0;
          }};
}

} // namespace curvetet::app

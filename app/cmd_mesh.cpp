// The main job, `curvetet MESH -o OUT.msh [options]`: input checks, then the
// whole pipeline (pipeline/pipeline.hpp); the mesh is written only when the
// re-verification of the result passes every guarantee.
#include "commands.hpp"
#include "input_stage.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/io/map_file.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/vtu.hpp"
#include "curvetet/map/build_map.hpp"
#include "curvetet/map/transfer.hpp"
#include "curvetet/mesh/surface_mesh.hpp"
#include "curvetet/pipeline/pipeline.hpp"

#include <map>
#include <memory>

namespace curvetet::app {

std::function<int()> add_mesh_options(CLI::App& root) {
  struct Options {
    InputOptions input;
    std::string output, vtu, map_path, report_path;
    bool binary = false;
    double epsilon_abs = 0;
    pipeline::PipelineOptions pipeline;
  };
  auto o = std::make_shared<Options>();
  add_input_options(root, o->input);
  root.add_option("-o,--output", o->output,
                  "Output mesh (.msh, Gmsh 4.1): order-P tets in \"domain\", boundary in \"boundary\", feature curves "
                  "(with --features / --feature-angle) as lines in \"features\"");
  root.add_option("--order", o->pipeline.order, "Order P of the output tets (middle surface of degree P-1)")
      ->check(CLI::Range(2, 6))
      ->capture_default_str();
  root.add_option("--epsilon", o->pipeline.epsilon, "Distance bound, relative to the input's bbox diagonal")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  root.add_option("--epsilon-abs", o->epsilon_abs, "Distance bound in absolute units (overrides --epsilon)")
      ->check(CLI::PositiveNumber);
  root.add_option("--fill", o->pipeline.fill,
                  "Regions to mesh: interior (the solid) or all (also the space out to a box, tets in \"exterior\", "
                  "box faces in \"box\")")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, pipeline::FillRegion>{{"interior", pipeline::FillRegion::interior},
                                                      {"all", pipeline::FillRegion::all}},
          CLI::ignore_case))
      ->default_str("interior");
  root.add_option("--box-margin", o->pipeline.box_margin,
                  "With --fill all: box margin around the shell, relative to its bbox diagonal")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  root.add_flag("!--no-optimize", o->pipeline.optimize,
                "Skip the curved optimization (certified collapses, flips, splits and smoothing)");
  root.add_option("--thickness", o->pipeline.shell.extrusion.target_thickness,
                  "Shell pillar length to grow to on each side, relative to the bbox diagonal")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  root.add_option("--thickness-ratio", o->pipeline.thickness_ratio,
                  "For thin parts: keep each boundary triangle's longest edge within K x the solid's thickness under "
                  "it (3-4: no flat tets across thin walls and tubes, more tets; default: no such rule)")
      ->check(CLI::PositiveNumber);
  root.add_flag("!--no-thin-retry", o->pipeline.thin_part_retry,
                "Do not run again with --thickness-ratio 3 (then 2) when the elements miss max AMIPS 30 or min "
                "scaled Jacobian 0.02 (by default a retry's output is kept if it meets both or is better in both)");
  root.add_flag("--slab-layer", o->pipeline.slab_layer,
                "Fill inside the shell's bottom surface and keep the bottom slabs (the paper's assembly; by default "
                "the interior is filled straight on the middle surface whenever all its tets certify)");
  root.add_flag("!--no-coarsen", o->pipeline.coarsen, "Keep the shell as dense as the input (no coarsening)");
  root.add_flag("!--flat-middle", o->pipeline.curved_middle,
                "Keep the middle surface flat (straight elements; coarser meshes come from the curved default)");
  root.add_option("--vtu", o->vtu, "Also write a VTK Lagrange .vtu (for ParaView) with per-tet min_scaled_jacobian and max_amips");
  root.add_option("--map", o->map_path,
                  "Also write the bijective map input <-> output boundary (binary; JSON if FILE ends in .json; "
                  "docs/map_format.md)");
  root.add_flag("--binary", o->binary, "Write the .msh in binary");
  root.add_flag("--debug-invariants", o->pipeline.shell.debug_invariants,
                "Re-check every shell invariant globally after each stage (slow)");
  root.add_option("--report", o->report_path, "Write the JSON report (counts, timings, guarantees) to FILE");
  return [o]() {
    Report report;
    auto in = read_checked_input(o->input, report);
    logger().info("{}: {}", o->input.mesh_path, in.preconditions.text());
    int code = 0;
    if (!o->output.empty() || !o->vtu.empty() || !o->map_path.empty()) {
      if (o->epsilon_abs > 0) o->pipeline.epsilon_abs = o->epsilon_abs;
      o->pipeline.constraint_points = in.features.points;
      auto result = pipeline::run_pipeline(in.mesh, o->pipeline, report, &in.feature_graph);
      const auto& v = result.verification;
      logger().info("result: {} tets of order {}, {} boundary triangles; {}", result.mesh.num_tets(), result.mesh.order,
                    result.mesh.num_boundary(), v.ok() ? "every guarantee verified" : "VERIFICATION FAILED");
      if (!v.ok()) {
        logger().error("{}", v.text());
        code = static_cast<int>(ExitCode::verification);
      } else {
        if (!o->output.empty())
          io::write_msh(o->output, result.mesh, o->binary ? io::MshFormat::v41_binary : io::MshFormat::v41_ascii);
        if (!o->vtu.empty())
          io::write_vtu(o->vtu, result.mesh,
                        {{"min_scaled_jacobian", v.min_scaled_jacobian}, {"max_amips", v.max_amips}});
        if (!o->map_path.empty()) {
          StageTimer t(&report, "map");
          map::MapBuildStats stats;
          const auto bmap = map::build_boundary_map(result.shell, result.mesh, &stats);
          io::write_map(o->map_path, bmap);
          // Distances relative to the input's bbox diagonal, like epsilon.
          const auto dist = map::map_distances(bmap);
          const double diag = mesh::bbox_diagonal(bmap.input.vertices);
          report["map"] = {{"path", o->map_path},
                           {"boundary_nodes", stats.nodes},
                           {"triangles", stats.triangles},
                           {"node_fallbacks", stats.node_fallbacks},
                           {"min_hit_depth", stats.min_hit_depth},
                           {"vertex_to_boundary_max", dist.vertex_max / diag},
                           {"node_to_input_max", dist.node_max / diag}};
          logger().info("map written to {} ({} input vertices, {} boundary nodes)", o->map_path,
                        bmap.input.vertices.size(), bmap.nodes.size());
        }
        logger().info("wrote {}{}", o->output, o->vtu.empty() ? "" : " and " + o->vtu);
      }
    }
    if (!o->report_path.empty()) {
      report.write(o->report_path);
      logger().info("report written to {}", o->report_path);
    }
    return code;
  };
}

} // namespace curvetet::app

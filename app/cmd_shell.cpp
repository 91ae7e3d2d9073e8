// `curvetet shell MESH -o DIR/ [--order P] [--epsilon E | --epsilon-abs A]
// [--no-coarsen] [--debug-invariants]`: builds the bijective prismatic shell,
// coarsens it under the distance bound (shell/coarsen.hpp), with --order P >= 3
// fitting a curved middle of degree P-1 in every operation, and writes
//   DIR/bottom.ply, DIR/middle.ply, DIR/top.ply  (same faces, 0-based ids)
//   DIR/middle.msh, DIR/middle.vtu  the (curved) middle surface as
//                    degree-(P-1) triangles (order 1 without --order)
//   DIR/map.txt      for each input vertex: middle face id and (u, v)
//                    (layout: io/write_vertex_map.hpp)
//   DIR/report.json  counts, thickness statistics, singular vertices, timings,
//                    coarsening: faces before/after, per pass operations
//                    tried/accepted/rejected per reason and seconds
// Everything is computed before the first file is written; each file is
// written atomically.
#include "commands.hpp"
#include "input_stage.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/vtu.hpp"
#include "curvetet/io/write_surface.hpp"
#include "curvetet/io/write_vertex_map.hpp"
#include "curvetet/shell/build.hpp"
#include "curvetet/shell/coarsen.hpp"
#include "curvetet/shell/curved_middle.hpp"
#include "curvetet/shell/feature_tracking.hpp"
#include "curvetet/features/refine.hpp"
#include "curvetet/shell/invariants.hpp"

#include <filesystem>
#include <memory>

namespace curvetet::app {

namespace {

nlohmann::json stats_json(const shell::ShellBuildStats& s) {
  return {{"input_vertices", s.input_vertices},
          {"input_faces", s.input_faces},
          {"singular_vertices", s.singular_vertices},
          {"split_edges", s.split_edges},
          {"initial_halvings", s.initial_halvings},
          {"thickening_rounds", s.rounds},
          {"growth_reverts", s.reverts},
          {"target_pillar", s.target_pillar},
          {"vertices_at_target", s.vertices_at_target},
          {"pillar_length", {{"min", s.min_pillar}, {"max", s.max_pillar}, {"mean", s.mean_pillar}}},
          {"thickness", {{"min", s.min_thickness}, {"max", s.max_thickness}, {"mean", s.mean_thickness}}}};
}

nlohmann::json coarsen_json(const shell::CoarsenStats& c) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& p : c.passes) {
    long long total = 0;
    for (long long n : p.rejected) total += n;
    passes.push_back({{"round", p.round},
                      {"operation", std::string(shell::to_string(p.op))},
                      {"faces_before", p.faces_before},
                      {"faces_after", p.faces_after},
                      {"tried", p.tried},
                      {"accepted", p.accepted},
                      {"rejected", total},
                      {"rejected_by_reason", shell::rejections_json(p)},
                      {"batches", p.batches},
                      {"seconds", p.seconds},
                      {"check_seconds", p.check_seconds}});
  }
  return {{"faces_before", c.faces_before},
          {"faces_after", c.faces_after},
          {"vertices_before", c.vertices_before},
          {"vertices_after", c.vertices_after},
          {"epsilon", c.epsilon},
          {"max_distance", c.max_distance},
          {"rounds", c.rounds},
          {"seconds", c.seconds},
          {"passes", passes}};
}

} // namespace

Command add_shell_command(CLI::App& root) {
  struct Options {
    InputOptions input;
    std::string out_dir;
    bool debug_invariants = false;
    bool no_coarsen = false;
    int order = 2;
    std::string format = "ply";
    shell::ShellOptions shell;
    shell::CoarsenOptions coarsen;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("shell", "Build the bijective prismatic shell of a surface and its vertex map");
  add_input_options(*cmd, o->input);
  cmd->add_option("-o,--output", o->out_dir, "Output directory (created if missing)")->required();
  cmd->add_flag("--debug-invariants", o->debug_invariants,
                "Re-check every shell invariant globally after each stage (slow; fails with exit code 3)");
  cmd->add_flag("--no-coarsen", o->no_coarsen, "Write the shell as built, without coarsening");
  cmd->add_option("--order", o->order,
                  "Output order P: the middle surface is curved of degree P-1 (2 = flat middle)")
      ->check(CLI::Range(2, 6))
      ->capture_default_str();
  auto* eps = cmd->add_option("--epsilon", o->coarsen.epsilon,
                              "Distance bound for coarsening, relative to the bbox diagonal")
                  ->check(CLI::PositiveNumber)
                  ->capture_default_str();
  cmd->add_option("--epsilon-abs", o->coarsen.epsilon_abs, "Distance bound for coarsening, absolute")
      ->check(CLI::PositiveNumber)
      ->excludes(eps);
  cmd->add_option("--coarsen-rounds", o->coarsen.max_rounds, "Maximum coarsening rounds")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--format", o->format, "Surface file format")->check(CLI::IsMember({"ply", "obj"}))->capture_default_str();
  cmd->add_option("--thickness", o->shell.extrusion.target_thickness,
                  "Target pillar length on each side, relative to the bbox diagonal")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--initial-thickness", o->shell.extrusion.initial_thickness,
                  "First pillar length tried, relative to the bbox diagonal (halved per vertex until valid)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--rounds", o->shell.extrusion.max_rounds, "Maximum thickening rounds")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  return {cmd, [o]() {
            Report report;
            auto in = read_checked_input(o->input, report);
            o->shell.debug_invariants = o->debug_invariants;
            // With features: faces with 2+ feature edges are refined 1-to-3
            // first (paper §5; vertex ids kept), then the chains are attached.
            const auto& graph = in.feature_graph;
            const bool featured = !graph.chains.empty() || !graph.corners.empty();
            shell::ShellBuild built;
            {
              StageTimer t(&report, "shell build");
              if (featured) {
                auto refined = features::refine_multi_feature_faces(in.mesh, in.features.edges);
                report["features"]["refined_faces"] = refined.mesh.num_faces() - in.mesh.num_faces();
                built = shell::build_shell(refined.mesh, o->shell);
                shell::attach_features(built.shell, graph);
              } else {
                built = shell::build_shell(in.mesh, o->shell);
              }
            }
            const auto& st = built.stats;
            const auto& s = built.shell;
            report["shell"] = stats_json(st);
            report["shell"]["prisms"] = s.num_prisms();
            report["shell"]["seconds"] = {{"isolation_and_directions", st.seconds_isolation},
                                          {"initial_layer", st.seconds_initial},
                                          {"thickening", st.seconds_thickening},
                                          {"map", st.seconds_map},
                                          {"total", st.seconds_total}};
            std::vector<int> singular_ids;
            for (int v = 0; v < s.num_vertices(); ++v)
              if (s.singular[v]) singular_ids.push_back(v);
            report["shell"]["singular_vertex_ids"] = singular_ids;
            if (o->debug_invariants) {
              StageTimer t(&report, "shell global check");
              shell::require_valid_shell(s, "shell construction");
              report["shell"]["global_check"] = "passed";
            }
            logger().info("shell: {} prisms, {} singular vertices, thickness min {:.6g} mean {:.6g} (target pillar "
                          "{:.6g}, {} of {} vertices reached it)",
                          s.num_prisms(), st.singular_vertices, st.min_thickness, st.mean_thickness, st.target_pillar,
                          st.vertices_at_target, s.num_vertices());

            report["shell"]["coarsened"] = !o->no_coarsen;
            if (!o->no_coarsen) {
              StageTimer t(&report, "shell coarsen");
              // --debug-invariants: the global check after every pass.
              o->coarsen.debug_invariants = o->debug_invariants;
              o->coarsen.target_pillar = o->shell.extrusion.target_thickness;
              o->coarsen.singular_dot = o->shell.extrusion.singular_dot;
              std::unique_ptr<shell::MiddleFit> fit;
              if (o->order > 2) fit = std::make_unique<shell::CurvedMiddleFit>(o->order - 1);
              const auto c = shell::coarsen_shell(built.shell, o->coarsen, fit.get());
              report["coarsen"] = coarsen_json(c);
              if (const auto* curved = dynamic_cast<const shell::CurvedMiddleFit*>(fit.get())) {
                report["coarsen"]["curved_middle"] = curved->stats().json();
              }
              // The written shell is the coarse one (vertices renumbered).
              report["shell"]["prisms"] = s.num_prisms();
              singular_ids.clear();
              for (int v = 0; v < s.num_vertices(); ++v)
                if (s.singular[v]) singular_ids.push_back(v);
              report["shell"]["singular_vertex_ids"] = singular_ids;
              logger().info("coarsen: {} -> {} faces ({:.1f}x) in {:.2f} s, max distance {:.6g} (epsilon {:.6g})",
                            c.faces_before, c.faces_after, double(c.faces_before) / std::max(1, c.faces_after),
                            c.seconds, c.max_distance, c.epsilon);
              if (featured) {
                const auto fc = shell::check_features(s);
                report["features"]["check"] = {{"corners", fc.corners},
                                               {"corners_missing", fc.corners_missing},
                                               {"corners_moved", fc.corners_moved},
                                               {"chains", fc.chains},
                                               {"broken_chains", fc.broken_chains},
                                               {"coarse_edges", fc.coarse_edges},
                                               {"missing_edges", fc.missing_edges},
                                               {"max_distance", fc.max_distance},
                                               {"ok", fc.ok(c.epsilon)}};
                logger().info("features: {} corners ({} missing, {} moved), {} chains ({} broken) in {} coarse edges, "
                              "max distance along features {:.6g}",
                              fc.corners, fc.corners_missing, fc.corners_moved, fc.chains, fc.broken_chains,
                              fc.coarse_edges, fc.max_distance);
                if (!fc.ok(c.epsilon))
                  throw Error(ExitCode::internal, "feature preservation violated: " + fc.first_problem);
              }
            }

            // Input vertices only (refinement centroids follow them in s.points).
            std::vector<io::VertexMapRecord> map(in.mesh.num_vertices());
            for (std::size_t i = 0; i < map.size(); ++i)
              map[i] = {s.points[i].image.prism, s.points[i].image.u, s.points[i].image.v};

            namespace fs = std::filesystem;
            std::error_code ec;
            fs::create_directories(o->out_dir, ec);
            if (ec) throw Error(ExitCode::io, "cannot create output directory " + o->out_dir + ": " + ec.message());
            const fs::path dir(o->out_dir);
            const std::string ext = "." + o->format;
            {
              StageTimer t(&report, "write shell");
              io::SurfaceWriteOptions wo;
              wo.binary = false;
              io::write_surface((dir / ("bottom" + ext)).string(), shell::bottom_surface(s), wo);
              io::write_surface((dir / ("middle" + ext)).string(), shell::middle_surface(s), wo);
              io::write_surface((dir / ("top" + ext)).string(), shell::top_surface(s), wo);
              const auto middle = shell::middle_surface_mesh(s);
              io::write_msh((dir / "middle.msh").string(), middle);
              io::write_vtu((dir / "middle.vtu").string(), middle);
              io::write_vertex_map((dir / "map.txt").string(), map,
                                   {"input vertex i -> middle surface (middle" + ext + ") face and (u, v)",
                                    s.middle_nodes.empty()
                                        ? "point = (1-u-v)*P[F[face][0]] + u*P[F[face][1]] + v*P[F[face][2]]"
                                        : "point = the curved triangle `face` of middle.msh at (u, v)",
                                    "input: " + o->input.mesh_path});
            }
            report.write((dir / "report.json").string());
            logger().info("shell written to {}", o->out_dir);
            return 0;
          }};
}

} // namespace curvetet::app

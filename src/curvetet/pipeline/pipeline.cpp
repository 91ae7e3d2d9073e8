#include "curvetet/pipeline/pipeline.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/pipeline/features_stage.hpp"
#include "curvetet/shell/coarsen.hpp"
#include "curvetet/shell/extrusion.hpp"
#include "curvetet/shell/feature_tracking.hpp"
#include "curvetet/volume/assemble.hpp"
#include "curvetet/volume/fill.hpp"

namespace curvetet::pipeline {
namespace {

// Degree-k Lagrange nodes of the (still linear) middle triangles: the
// curved fit replaces these with fitted ones.
volume::CurvedMiddle linear_middle(const shell::Shell& s, int degree) {
  volume::CurvedMiddle m;
  m.bottom = s.bottom;
  m.faces = s.faces;
  m.singular = s.singular;
  m.degree = degree;
  const int n = highorder::triangle_node_count(degree);
  for (const auto& f : s.faces) {
    std::vector<mesh::Vec3> nodes;
    for (int i = 0; i < n; ++i) {
      auto l = highorder::triangle_node(degree, i);
      const double u = double(l[0]) / degree, v = double(l[1]) / degree;
      nodes.push_back((1 - u - v) * s.middle[f[0]] + u * s.middle[f[1]] + v * s.middle[f[2]]);
    }
    // Corners bit-exact (no rounding through the weights).
    for (int k = 0; k < 3; ++k) nodes[k] = s.middle[f[k]];
    m.middle_nodes.push_back(std::move(nodes));
  }
  return m;
}

mesh::LinearTetMesh fill_inside(const mesh::SurfaceMesh& bottom, double offset, volume::FillStats& stats) {
  shell::ExtrusionOptions ex;
  ex.target_thickness = offset;
  auto layer = shell::extrude_one_sided(bottom, shell::Side::inward, ex);
  volume::LayeredSurface ls{bottom, layer.offset, volume::OffsetSide::inward};
  return volume::fill_layered(ls, {}, &stats);
}

} // namespace

PipelineResult run_pipeline(const mesh::SurfaceMesh& input, const PipelineOptions& o, Report& report,
                            const features::FeatureGraph* features) {
  const bool featured = features && (!features->chains.empty() || !features->corners.empty());
  if (o.order < 2 || o.order > 6) throw Error(ExitCode::usage, "--order must be in 2..6");
  PipelineResult r;
  const double diagonal = mesh::bbox_diagonal(input.vertices);
  const double epsilon_rel = o.epsilon_abs ? *o.epsilon_abs / diagonal : o.epsilon;
  report["options"] = {{"order", o.order}, {"epsilon_relative", epsilon_rel}, {"bbox_diagonal", diagonal}};

  {
    StageTimer t(&report, "shell");
    auto built = shell::build_shell(featured ? refine_for_features(input, *features) : input, o.shell);
    r.shell = std::move(built.shell);
    if (featured) shell::attach_features(r.shell, *features);
    report["shell"] = {{"faces", r.shell.num_prisms()},
                       {"singular_vertices", built.stats.singular_vertices},
                       {"min_thickness", built.stats.min_thickness}};
  }

  if (o.coarsen) {
    StageTimer t(&report, "coarsen");
    shell::CoarsenOptions co;
    co.epsilon = epsilon_rel;
    co.target_pillar = o.shell.extrusion.target_thickness;
    co.singular_dot = o.shell.extrusion.singular_dot;
    co.debug_invariants = o.shell.debug_invariants;
    const auto c = shell::coarsen_shell(r.shell, co);
    report["coarsen"] = {{"faces_before", c.faces_before}, {"faces_after", c.faces_after},
                         {"rounds", c.rounds},             {"max_distance_relative", c.max_distance / diagonal},
                         {"epsilon_relative", epsilon_rel}};
    logger().info("coarsened the shell from {} to {} faces", c.faces_before, c.faces_after);
    if (featured) {
      const auto fc = shell::check_features(r.shell);
      report["features"] = {{"corners", fc.corners},       {"chains", fc.chains},
                            {"coarse_edges", fc.coarse_edges}, {"max_distance_relative", fc.max_distance / diagonal}};
      if (!fc.ok(c.epsilon)) throw Error(ExitCode::internal, "feature preservation violated: " + fc.first_problem);
    }
  }

  volume::CurvedMiddle middle;
  {
    StageTimer t(&report, "middle surface");
    middle = linear_middle(r.shell, 1); // flat until the curved fit (issue 7) provides degree P-1
  }

  mesh::LinearTetMesh fill;
  {
    StageTimer t(&report, "fill");
    volume::FillStats stats;
    fill = fill_inside(shell::bottom_surface(r.shell), o.fill_offset, stats);
    report["fill"] = {{"tets", fill.num_tets()}, {"max_amips", stats.max_amips}, {"mean_amips", stats.mean_amips}};
  }

  {
    StageTimer t(&report, "assemble");
    volume::AssemblyStats stats;
    r.mesh = volume::assemble_curved_mesh(middle, fill, o.order, &stats);
    if (featured) report["features"]["lines"] = add_feature_lines(r.mesh, r.shell);
    report["assembly"] = {{"fill_tets", stats.fill_tets},
                          {"slab_tets", stats.slab_tets},
                          {"pinched_slab_tets", stats.pinched_slab_tets},
                          {"boundary_triangles", stats.boundary_triangles}};
  }

  {
    StageTimer t(&report, "verify");
    check::TetMeshVerifyOptions vo;
    vo.input = &input;
    vo.epsilon = epsilon_rel;
    r.verification = check::verify_tet_mesh(r.mesh, vo);
    report["verification"] = r.verification.json();
  }
  return r;
}

} // namespace curvetet::pipeline

#include "curvetet/pipeline/pipeline.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/pipeline/features_stage.hpp"
#include "curvetet/shell/coarsen.hpp"
#include "curvetet/shell/curved_middle.hpp"
#include "curvetet/shell/extrusion.hpp"
#include "curvetet/shell/feature_tracking.hpp"
#include "curvetet/volume/assemble.hpp"
#include "curvetet/volume/assemble_middle.hpp"
#include "curvetet/volume/fill.hpp"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>

namespace curvetet::pipeline {
namespace {

// Coarsening bounds of the output (measured on bunny_libigl, P = 4,
// eps = 1%: docs/pipeline_e2e.md). The middle triangles' MIPS bound (the
// shell's default is 30) and the slab rule keep sliver triangles and long
// faces over thin parts (the ears) out: those made the flattest output
// tets (slab bound: AMIPS 150 in highorder/quality.hpp's convention, where
// the regular tet has 3). The fill's collapses and flips may create tets up
// to energy 100 (volume/tet_amips.hpp's unit, a third of AMIPS: 300; the
// curved optimization improves them afterwards: a coarse fill is what makes
// the output coarser than the reference's) but no edge longer than 4x the
// mean bottom edge, so the interior refines with the surface as epsilon
// drops (tests/fem/test_poisson_epsilon.cpp).
constexpr double kMiddleQualityBound = 10;
constexpr double kSlabQualityBound = 150;
// Fitted middle patches: 2D MIPS up to 25 on their lattice (fertility's
// worst tet sat under a patch of 42-77; lower bounds reshuffle smooth
// models, docs/usable_elements.md).
constexpr double kCurvedQualityBound = 25;
constexpr double kFillCoarsenEnergy = 100;
constexpr double kFillEdgeFactor = 4;
// The thickness rule's ratios of the retries (PipelineOptions::thin_part_retry).
// The next runs only when the last was kept and meets one target: then thin
// parts are what held the elements back. Where both targets are still
// missed, the worst elements come from what the rule does not change
// (needle input triangles, a forced tet): measured in docs/usable_elements.md
// (session 38), a stricter ratio did not help there.
constexpr std::array<double, 2> kThinPartRatios = {3, 2};

// The shell's middle surface as the assembly takes it: its fitted nodes, or
// the flat triangles (degree 1) when it was not curved.
volume::CurvedMiddle middle_of(const shell::Shell& s) {
  volume::CurvedMiddle m;
  m.bottom = s.bottom;
  m.faces = s.faces;
  m.singular = s.singular;
  m.straight_slab_parts = s.straight_slab_parts;
  m.degree = s.middle_nodes.empty() ? 1 : s.middle_degree;
  if (!s.middle_nodes.empty()) m.middle_nodes = s.middle_nodes;
  else
    for (const auto& f : s.faces) m.middle_nodes.push_back(shell::flat_triangle_nodes({s.middle[f[0]], s.middle[f[1]], s.middle[f[2]]}, 1));
  return m;
}

mesh::LinearTetMesh fill_inside(const mesh::SurfaceMesh& bottom, double offset, volume::FillStats& stats) {
  shell::ExtrusionOptions ex;
  ex.target_thickness = offset;
  auto layer = shell::extrude_one_sided(bottom, shell::Side::inward, ex);
  volume::LayeredSurface ls{bottom, layer.offset, volume::OffsetSide::inward};
  volume::FillOptions fo;
  fo.coarsen_energy = kFillCoarsenEnergy;
  fo.max_edge_length = kFillEdgeFactor * mesh::mean_edge_length(bottom);
  return volume::fill_layered(ls, fo, &stats);
}

// Between the top surface and a box (vertices [0, n) = the top's).
mesh::LinearTetMesh fill_outside(const mesh::SurfaceMesh& top, double offset, double margin, volume::FillStats& stats) {
  shell::ExtrusionOptions ex;
  ex.target_thickness = offset;
  auto layer = shell::extrude_one_sided(top, shell::Side::outward, ex);
  volume::LayeredSurface ls{top, layer.offset, volume::OffsetSide::outward};
  volume::FillOptions fo;
  fo.box_margin = margin;
  return volume::fill_layered(ls, fo, &stats);
}

// Tets of m the certificate does not prove positive (parallel).
int uncertified_tets(const mesh::TetMesh& m) {
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(0, m.num_tets()), 0,
      [&](const tbb::blocked_range<int>& r, int n) {
        std::vector<mesh::Vec3> nodes(m.tet_nodes());
        for (int t = r.begin(); t < r.end(); ++t) {
          m.tet_positions(t, nodes.data());
          n += highorder::certify_tet(m.order, nodes.data()).validity != highorder::Validity::positive;
        }
        return n;
      },
      std::plus<>());
}

// The paper's assembly: the fill inside the bottom surface (and with --fill
// all outside the top one) plus the slabs. False when a curved middle's
// tets are not all certified (*uncertified says how many).
bool assemble_with_slabs(PipelineResult& r, volume::CurvedMiddle& middle, const PipelineOptions& o, bool featured,
                         Report& report, int* uncertified) {
  mesh::LinearTetMesh fill;
  {
    StageTimer t(&report, "fill");
    volume::FillStats stats;
    fill = fill_inside(shell::bottom_surface(r.shell), o.fill_offset, stats);
    report["fill"] = {{"tets", fill.num_tets()},
                      {"max_amips", stats.max_amips},
                      {"mean_amips", stats.mean_amips},
                      {"min_scaled_jacobian", stats.min_scaled_jacobian},
                      {"rejected", stats.rejected_json()}};
  }

  mesh::LinearTetMesh exterior;
  if (o.fill == FillRegion::all) {
    StageTimer t(&report, "fill exterior");
    volume::FillStats stats;
    exterior = fill_outside(shell::top_surface(r.shell), o.fill_offset, o.box_margin, stats);
    middle.top = r.shell.top;
    report["fill_exterior"] = {{"tets", exterior.num_tets()},
                               {"max_amips", stats.max_amips},
                               {"mean_amips", stats.mean_amips},
                               {"min_scaled_jacobian", stats.min_scaled_jacobian}};
  }

  {
    StageTimer t(&report, "assemble");
    volume::AssemblyStats stats;
    r.mesh = volume::assemble_curved_mesh(middle, fill, o.order, &stats,
                                          o.fill == FillRegion::all ? &exterior : nullptr);
    if (featured) report["features"]["lines"] = add_feature_lines(r.mesh, r.shell);
    report["assembly"] = {{"fill_tets", stats.fill_tets},
                          {"slab_tets", stats.slab_tets},
                          {"pinched_slab_tets", stats.pinched_slab_tets},
                          {"boundary_triangles", stats.boundary_triangles}};
    if (o.fill == FillRegion::all)
      report["assembly"].update({{"exterior_fill_tets", stats.exterior_fill_tets},
                                 {"top_slab_tets", stats.top_slab_tets},
                                 {"box_triangles", stats.box_triangles}});
    if (uncertified && r.shell.middle_degree > 1 && !r.shell.middle_nodes.empty()) {
      *uncertified = uncertified_tets(r.mesh);
      if (*uncertified > 0) return false;
    }
  }
  return true;
}

// One run of the stages. With a curved middle, returns early with
// *uncertified > 0 when the assembled tets are not all certified positive
// (the caller then runs again with a flat middle).
// The features file's points, on `input` (whose vertex ids the shell's
// input keeps when it refines faces for features).
void add_constraint_points(shell::Shell& s, const mesh::SurfaceMesh& input, const features::ConstraintPoints& points) {
  std::vector<mesh::Vec3> positions;
  std::vector<shell::Tri> near;
  for (std::size_t i = 0; i < points.faces.size(); ++i) {
    const auto& f = input.faces[points.faces[i]];
    const auto& b = points.barycentric[i];
    positions.push_back(b[0] * input.vertices[f[0]] + b[1] * input.vertices[f[1]] + b[2] * input.vertices[f[2]]);
    near.push_back(f);
  }
  shell::add_constraint_points(s, positions, near);
}

PipelineResult run_stages(const mesh::SurfaceMesh& input, const PipelineOptions& o, Report& report,
                          const features::FeatureGraph* features, int* uncertified) {
  const bool featured = features && (!features->chains.empty() || !features->corners.empty());
  if (o.order < 2 || o.order > 6) throw Error(ExitCode::usage, "--order must be in 2..6");
  PipelineResult r;
  const double diagonal = mesh::bbox_diagonal(input.vertices);
  const double epsilon_rel = o.epsilon_abs ? *o.epsilon_abs / diagonal : o.epsilon;
  report["options"] = {{"order", o.order}, {"epsilon_relative", epsilon_rel}, {"bbox_diagonal", diagonal}};
  if (std::isfinite(o.thickness_ratio)) report["options"]["thickness_ratio"] = o.thickness_ratio;

  {
    StageTimer t(&report, "shell");
    auto built = shell::build_shell(featured ? refine_for_features(input, *features) : input, o.shell);
    r.shell = std::move(built.shell);
    if (featured) shell::attach_features(r.shell, *features);
    add_constraint_points(r.shell, input, o.constraint_points);
    report["shell"] = {{"faces", r.shell.num_prisms()},
                       {"constraint_points", o.constraint_points.faces.size()},
                       {"singular_vertices", built.stats.singular_vertices},
                       {"min_thickness", built.stats.min_thickness}};
  }

  if (o.coarsen) {
    StageTimer t(&report, "coarsen");
    shell::CoarsenOptions co;
    co.epsilon = epsilon_rel;
    co.target_pillar = o.shell.extrusion.target_thickness;
    co.quality_bound = kMiddleQualityBound;
    co.slab_quality_bound = kSlabQualityBound;
    co.curved_quality_bound = kCurvedQualityBound;
    co.thickness_ratio = o.thickness_ratio;
    co.singular_dot = o.shell.extrusion.singular_dot;
    co.debug_invariants = o.shell.debug_invariants;
    // Middle of degree P-1 (paper §4.1); P = 2 keeps it flat.
    std::unique_ptr<shell::MiddleFit> fit;
    if (o.order > 2 && o.curved_middle) fit = std::make_unique<shell::CurvedMiddleFit>(o.order - 1);
    const auto c = shell::coarsen_shell(r.shell, co, fit.get());
    report["coarsen"] = {{"faces_before", c.faces_before}, {"faces_after", c.faces_after},
                         {"rounds", c.rounds},
                         {"middle_degree", r.shell.middle_nodes.empty() ? 1 : r.shell.middle_degree},
                         {"max_distance_relative", c.max_distance / diagonal},
                         {"max_surface_distance_relative", c.max_surface_distance / diagonal},
                         {"epsilon_relative", epsilon_rel}};
    if (const auto* curved = dynamic_cast<const shell::CurvedMiddleFit*>(fit.get()))
      report["coarsen"]["curved_middle"] = curved->stats().json();
    // Why candidates were turned down, summed over every pass (what limits
    // the coarsening: distance, surface distance, quality, ...).
    report["coarsen"]["rejected"] = shell::rejections_json(c.passes);
    report["coarsen"]["check_cpu_seconds"] = shell::check_seconds_json(c.passes);
    logger().info("coarsened the shell from {} to {} faces", c.faces_before, c.faces_after);
    if (featured) {
      const auto fc = shell::check_features(r.shell);
      report["features"] = {{"corners", fc.corners},       {"chains", fc.chains},
                            {"coarse_edges", fc.coarse_edges}, {"max_distance_relative", fc.max_distance / diagonal}};
      if (!fc.ok(c.epsilon))
        throw Error(ExitCode::internal,
                    "feature preservation violated: " +
                        (fc.first_problem.empty() ? fmt::format("feature distance {:.6g} >= epsilon {:.6g}",
                                                                fc.max_distance, c.epsilon)
                                                  : fc.first_problem));
    }
  }

  volume::CurvedMiddle middle;
  {
    StageTimer t(&report, "middle surface");
    middle = middle_of(r.shell);
  }

  // The interior on the middle surface; the paper's assembly (fill inside
  // the bottom surface, every bottom slab) with --fill all or --slab-layer,
  // or should the former have no fill or some tet not certify
  // (report "assembly_on_middle" then says which).
  bool assembled = false;
  if (o.fill == FillRegion::interior && !o.slab_layer) {
    StageTimer t(&report, "assemble");
    nlohmann::json attempt;
    assembled = volume::assemble_on_middle(middle, o.order, r.mesh, attempt);
    if (assembled) {
      report["assembly"] = attempt;
      if (featured) report["features"]["lines"] = add_feature_lines(r.mesh, r.shell);
    } else {
      logger().info("the assembly on the middle surface {}; taking the slab assembly",
                    attempt.contains("uncertified_tets")
                        ? fmt::format("leaves {} tets uncertified", attempt["uncertified_tets"].get<int>())
                        : "has no fill");
      report["assembly_on_middle"] = attempt;
    }
  }
  if (!assembled && !assemble_with_slabs(r, middle, o, featured, report, uncertified)) return r;

  if (o.optimize) {
    StageTimer t(&report, "curved optimization");
    const auto st = volume::remesh_curved(r.mesh, o.optimization);
    report["curved_optimization"] = st.json();
    logger().info("curved optimization: {} -> {} tets, max AMIPS {:.4g} -> {:.4g}, min scaled Jacobian {:.3g} -> "
                  "{:.3g} ({} collapses, {} flips, {} vertex and {} node moves)",
                  st.tets_before, st.tets_after, st.max_amips_before, st.max_amips_after,
                  st.min_scaled_jacobian_before, st.min_scaled_jacobian_after, st.collapses,
                  st.flips_2_3 + st.flips_3_2 + st.flips_4_4 + st.edge_removals, st.vertex_moves, st.node_moves);
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

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// run_stages, and again with a flat middle should an assembled tet not be
// certified with the curved one.
PipelineResult run_with_fallback(const mesh::SurfaceMesh& input, const PipelineOptions& o, Report& report,
                                 const features::FeatureGraph* features) {
  int uncertified = 0;
  const auto start = std::chrono::steady_clock::now();
  auto r = run_stages(input, o, report, features, &uncertified);
  if (uncertified == 0) return r;
  // The shell certifies the very tets the assembly makes wherever they leave
  // the slab map (shell/slab_tet_nodes), from its first layer on (checked by
  // --debug-invariants, nefertiti included), so this is not expected to
  // run; it keeps the output valid should an assembled tet still not be
  // certified: a flat middle's tets are straight, positive by the prism
  // invariant.
  const double seconds = seconds_since(start);
  logger().warn("{} assembled tets are not certified positive with the curved middle; running again with a flat "
                "middle",
                uncertified);
  PipelineOptions flat = o;
  flat.curved_middle = false;
  r = run_stages(input, flat, report, features, nullptr); // rewrites every stage's entry
  report["curved_middle_fallback"] = {{"uncertified_tets", uncertified}, {"seconds_of_the_curved_run", seconds}};
  return r;
}

bool meets_targets(const check::TetMeshVerification& v, const PipelineOptions& o) {
  return v.worst_amips <= o.target_max_amips && v.worst_scaled_jacobian >= o.target_min_scaled_jacobian;
}

bool meets_one_target(const check::TetMeshVerification& v, const PipelineOptions& o) {
  return v.worst_amips <= o.target_max_amips || v.worst_scaled_jacobian >= o.target_min_scaled_jacobian;
}

// Whether a's worst elements are at least as good as b's in both measures
// and better in one.
bool better_in_both(const check::TetMeshVerification& a, const check::TetMeshVerification& b) {
  const bool no_worse = a.worst_amips <= b.worst_amips && a.worst_scaled_jacobian >= b.worst_scaled_jacobian;
  return no_worse && (a.worst_amips < b.worst_amips || a.worst_scaled_jacobian > b.worst_scaled_jacobian);
}

nlohmann::json run_summary(const PipelineResult& r, double seconds) {
  return {{"tets", r.mesh.num_tets()},
          {"boundary_triangles", r.mesh.num_boundary()},
          {"max_amips", r.verification.worst_amips},
          {"min_scaled_jacobian", r.verification.worst_scaled_jacobian},
          {"seconds", seconds}};
}

} // namespace

PipelineResult run_pipeline(const mesh::SurfaceMesh& input, const PipelineOptions& o, Report& report,
                            const features::FeatureGraph* features) {
  const auto start = std::chrono::steady_clock::now();
  auto r = run_with_fallback(input, o, report, features);
  const bool may_retry = o.thin_part_retry && o.coarsen && !std::isfinite(o.thickness_ratio);
  if (!may_retry || !r.verification.ok() || meets_targets(r.verification, o)) return r;
  const nlohmann::json first = run_summary(r, seconds_since(start));
  logger().info("max AMIPS {:.4g}, min scaled Jacobian {:.3g} miss the targets ({:.4g}, {:.3g})",
                r.verification.worst_amips, r.verification.worst_scaled_jacobian, o.target_max_amips,
                o.target_min_scaled_jacobian);
  // Thin walls and sheets under long coarse triangles leave only flat tets
  // between them, which no operation of the volume stage can improve
  // (docs/usable_elements.md, session 37); the thickness rule avoids them
  // at the price of more tets, and moves the coarsening of other models
  // either way. So it runs only as a retry, whose output is kept when it
  // meets the targets or is better in both measures than the one kept.
  nlohmann::json retries = nlohmann::json::array();
  double kept_ratio = 0;
  for (const double ratio : kThinPartRatios) {
    logger().info("running again with --thickness-ratio {}", ratio);
    PipelineOptions thin = o;
    thin.thickness_ratio = ratio;
    Report attempt = report;
    const auto start_attempt = std::chrono::steady_clock::now();
    auto again = run_with_fallback(input, thin, attempt, features);
    const bool keep = again.verification.ok() && (meets_targets(again.verification, o) ||
                                                  better_in_both(again.verification, r.verification));
    auto summary = run_summary(again, seconds_since(start_attempt));
    summary["thickness_ratio"] = ratio;
    summary["kept"] = keep;
    retries.push_back(std::move(summary));
    logger().info("max AMIPS {:.4g}, min scaled Jacobian {:.3g}, {} tets: {}", again.verification.worst_amips,
                  again.verification.worst_scaled_jacobian, again.mesh.num_tets(), keep ? "kept" : "not kept");
    if (!keep) break;
    kept_ratio = ratio;
    report = std::move(attempt);
    r = std::move(again);
    if (meets_targets(r.verification, o) || !meets_one_target(r.verification, o)) break;
  }
  report["thin_part_retry"] = {{"first", first},
                               {"retries", std::move(retries)},
                               {"kept_thickness_ratio", kept_ratio > 0 ? nlohmann::json(kept_ratio) : nlohmann::json()}};
  return r;
}

} // namespace curvetet::pipeline

#include "input_stage.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/features/detect.hpp"
#include "curvetet/io/features_json.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/mesh/edge_topology.hpp"

#include <algorithm>

namespace curvetet::app {

void add_input_options(CLI::App& cmd, InputOptions& o) {
  cmd.add_option("MESH", o.mesh_path, "Input surface: .off, .obj, .stl or .ply (closed, manifold, oriented)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd.add_option("--features", o.features_path, "Feature/constraint file (JSON, 0-based): edges, corners, points")
      ->check(CLI::ExistingFile);
  cmd.add_option("--feature-set", o.feature_set, "Which feature edges of the file to use")
      ->check(CLI::IsMember({"all", "sharp"}))
      ->capture_default_str();
  cmd.add_option("--feature-angle", o.feature_angle, "Also mark edges whose dihedral angle exceeds DEG as features")
      ->check(CLI::Range(0.0, 180.0));
}

CheckedInput read_checked_input(const InputOptions& o, Report& report) {
  CheckedInput in;
  mesh::PolygonSoup soup;
  {
    StageTimer t(&report, "read input");
    soup = io::read_surface(o.mesh_path);
  }
  {
    StageTimer t(&report, "check input");
    in.preconditions = check::check_preconditions(soup);
    report["input"] = in.preconditions.json();
    report["input"]["path"] = o.mesh_path;
    if (!in.preconditions.ok()) {
      auto code = in.preconditions.exit_code();
      throw Error(static_cast<InputDefect>(code - exit_code(InputDefect::unreadable)),
                  o.mesh_path + ": " + in.preconditions.text());
    }
    in.mesh = mesh::to_surface_mesh(soup);
  }
  if (!o.features_path.empty() || o.feature_angle) {
    StageTimer t(&report, "read features");
    auto topo = mesh::build_edge_topology(in.mesh.faces);
    if (!o.features_path.empty()) {
      in.features = io::read_features(o.features_path, o.feature_set == "sharp" ? io::FeatureSet::sharp : io::FeatureSet::all);
      features::validate_and_normalize(in.features, in.mesh, topo);
    }
    if (o.feature_angle) {
      auto detected = features::detect_feature_edges(in.mesh, topo, *o.feature_angle);
      logger().info("--feature-angle {}: {} feature edges detected", *o.feature_angle, detected.size());
      in.features.edges.insert(in.features.edges.end(), detected.begin(), detected.end());
      features::validate_and_normalize(in.features, in.mesh, topo);
    }
    in.feature_graph = features::group_features(in.mesh.num_vertices(), in.features.edges, in.features.corners);
    const auto loops = std::count_if(in.feature_graph.chains.begin(), in.feature_graph.chains.end(),
                                     [](const features::FeatureChain& c) { return c.closed; });
    report["features"] = {{"edges", in.features.edges.size()},
                          {"user_corners", in.features.corners.size()},
                          {"corners", in.feature_graph.corners.size()},
                          {"chains", in.feature_graph.chains.size() - loops},
                          {"loops", loops},
                          {"points", in.features.points.faces.size()}};
    logger().info("features: {} edges in {} chains and {} loops, {} corners", in.features.edges.size(),
                  in.feature_graph.chains.size() - loops, loops, in.feature_graph.corners.size());
  }
  return in;
}

} // namespace curvetet::app

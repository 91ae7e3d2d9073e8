#pragma once
// Reading and checking the input surface and its features: shared by the
// subcommands that take an input mesh, so all report defects the same way.
#include "curvetet/check/preconditions.hpp"
#include "curvetet/core/report.hpp"
#include "curvetet/features/chains.hpp"
#include "curvetet/features/feature_input.hpp"
#include "curvetet/mesh/surface_mesh.hpp"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace curvetet::app {

struct InputOptions {
  std::string mesh_path;
  std::string features_path;
  std::string feature_set = "all"; // "all" or "sharp"
  std::optional<double> feature_angle;
};

// Adds MESH, --features, --feature-set, --feature-angle to a command.
void add_input_options(CLI::App& cmd, InputOptions& options);

struct CheckedInput {
  mesh::SurfaceMesh mesh;
  features::FeatureInput features;
  features::FeatureGraph feature_graph; // empty without features
  check::PreconditionReport preconditions;
};

// Reads and validates everything; throws curvetet::Error with the defect's
// exit code. Records counts and timings in `report`.
CheckedInput read_checked_input(const InputOptions& options, Report& report);

} // namespace curvetet::app

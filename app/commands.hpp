#pragma once
// Each subcommand registers itself on the CLI11 app and returns the function
// that runs it; options live in structs owned by that function (STYLE.md 9).
#include <CLI/CLI.hpp>

#include <functional>

namespace curvetet::app {

struct Command {
  CLI::App* cli = nullptr;
  std::function<int()> run;
};

Command add_check_input_command(CLI::App& root);
Command add_check_command(CLI::App& root);
Command add_shell_command(CLI::App& root);
Command add_poisson_command(CLI::App& root);
Command add_tetrahedralize_command(CLI::App& root);
Command add_transfer_command(CLI::App& root);
Command add_deform_command(CLI::App& root);
// The main job: options live on the root app itself (`curvetet MESH ...`).
std::function<int()> add_mesh_options(CLI::App& root);

} // namespace curvetet::app

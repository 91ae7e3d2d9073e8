// curvetet command line. Library errors arrive as curvetet::Error and become
// exit codes here (src/curvetet/core/error.hpp lists them).
#include "commands.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/core/threads.hpp"

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
  using namespace curvetet;
  CLI::App root{"curvetet: coarse, curved, certified-valid tetrahedral meshes with a bijective boundary map"};
  root.set_version_flag("--version", "curvetet 0.1.0");
  int verbose = 0, threads = 0;
  bool quiet = false;
  root.add_flag("-v,--verbose", verbose, "More log output (debug)");
  root.add_flag("-q,--quiet", quiet, "Only warnings and errors");
  root.add_option("--threads", threads, "Worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  root.require_subcommand(0, 1);
  root.fallthrough();

  std::vector<app::Command> commands = {app::add_check_input_command(root), app::add_check_command(root),
                                        app::add_shell_command(root), app::add_tetrahedralize_command(root),
                                        app::add_poisson_command(root),
                                        app::add_transfer_command(root), app::add_deform_command(root)};
  auto run_main_job = app::add_mesh_options(root);
  // The main job's MESH is required only when no subcommand is given.
  root.get_option("MESH")->required(false);

  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = root.exit(e);
    return code == 0 ? 0 : static_cast<int>(ExitCode::usage);
  }
  set_verbosity(quiet ? 0 : 1 + verbose);
  ThreadLimit limit(threads);

  try {
    for (const auto& c : commands)
      if (c.cli->parsed()) return c.run();
    if (root.get_option("MESH")->empty()) {
      std::cerr << root.help();
      return static_cast<int>(ExitCode::usage);
    }
    return run_main_job();
  } catch (const Error& e) {
    logger().error("{}", e.what());
    return e.code();
  } catch (const std::exception& e) {
    logger().critical("internal error: {}", e.what());
    return static_cast<int>(ExitCode::internal);
  }
}

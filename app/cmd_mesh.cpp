// The main job, `curvetet MESH [options]`. Runs every pipeline stage that
// exists so far (today: input reading, precondition checks, features) and
// prints/writes the report.
#include "commands.hpp"
#include "input_stage.hpp"

#include "curvetet/core/log.hpp"

#include <memory>

namespace curvetet::app {

std::function<int()> add_mesh_options(CLI::App& root) {
  struct Options {
    InputOptions input;
    std::string report_path;
  };
  auto o = std::make_shared<Options>();
  add_input_options(root, o->input);
  root.add_option("--report", o->report_path, "Write the JSON report (counts, timings, checks) to FILE");
  return [o]() {
    Report report;
    auto in = read_checked_input(o->input, report);
    logger().info("{}: {}", o->input.mesh_path, in.preconditions.text());
    if (!o->report_path.empty()) {
      report.write(o->report_path);
      logger().info("report written to {}", o->report_path);
    }
    return 0;
  };
}

} // namespace curvetet::app

// `curvetet check-input MESH [--features FILE] [--json]`: reports every input
// defect in words (or JSON on stdout) and exits with the first defect's code.
#include "commands.hpp"
#include "input_stage.hpp"

#include "curvetet/core/error.hpp"

#include <iostream>
#include <memory>

namespace curvetet::app {

Command add_check_input_command(CLI::App& root) {
  struct Options {
    InputOptions input;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("check-input", "Check that a surface meets curvetet's input preconditions");
  add_input_options(*cmd, o->input);
  cmd->add_flag("--json", o->json, "Print the report as JSON on stdout");
  return {cmd, [o]() {
            Report report;
            int code = 0;
            std::string message;
            try {
              auto in = read_checked_input(o->input, report);
              message = o->input.mesh_path + ": " + in.preconditions.text();
            } catch (const Error& e) {
              code = e.code();
              message = e.what();
              report["error"] = {{"exit_code", code}, {"message", message}};
            }
            if (o->json)
              std::cout << report.json().dump(2) << '\n';
            else
              std::cout << message << '\n';
            return code;
          }};
}

} // namespace curvetet::app

#pragma once
// Typed errors and the program's exit codes. Library code never calls exit();
// it throws curvetet::Error, and app/main.cpp turns it into the exit code.
#include <stdexcept>
#include <string>
#include <string_view>

namespace curvetet {

// Exit codes of the curvetet program. Input defects have one code each
// (10 + the defect's index in InputDefect), so scripts can tell them apart.
enum class ExitCode : int {
  ok = 0,
  usage = 2,             // bad command line (CLI11 also uses 1..2 for this)
  internal = 3,          // a bug: an invariant failed that should not
  io = 4,                // cannot write an output file
  verification = 5,      // `check`: the mesh fails a guarantee
  input_defect_base = 10 // + InputDefect index
};

// Defect classes of an input surface, in the order they are checked.
// Order matters: the exit code of a run with several defects is the code of
// the first class found (the most fundamental one).
enum class InputDefect : int {
  unreadable = 0,          // missing/unparseable file or no faces
  non_finite,              // NaN or infinite coordinate
  index_out_of_range,      // face refers to a missing vertex
  non_triangle,            // polygon with != 3 corners
  duplicate_face,          // two faces on the same three vertices
  degenerate_triangle,     // exactly zero area (collinear / coincident)
  nonmanifold_edge,        // edge with more than two faces
  nonmanifold_vertex,      // vertex whose faces form several fans
  open_boundary,           // edge with one face
  inconsistent_orientation,// edge used twice in the same direction
  wrong_orientation,       // component not bounding a solid outward (cavity inward)
  self_intersection,       // non-adjacent faces meet, or adjacent ones overlap
  bad_features,            // feature file invalid for this mesh
  count
};

std::string_view to_string(InputDefect d);
int exit_code(InputDefect d);

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& what) : std::runtime_error(what), code_(static_cast<int>(code)) {}
  Error(InputDefect defect, const std::string& what)
      : std::runtime_error(what), code_(exit_code(defect)) {}
  int code() const { return code_; }

 private:
  int code_;
};

} // namespace curvetet

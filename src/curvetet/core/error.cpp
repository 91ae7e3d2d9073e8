#include "curvetet/core/error.hpp"

namespace curvetet {

std::string_view to_string(InputDefect d) {
  switch (d) {
    case InputDefect::unreadable: return "unreadable";
    case InputDefect::non_finite: return "non_finite_coordinate";
    case InputDefect::index_out_of_range: return "index_out_of_range";
    case InputDefect::non_triangle: return "non_triangle_face";
    case InputDefect::duplicate_face: return "duplicate_face";
    case InputDefect::degenerate_triangle: return "degenerate_triangle";
    case InputDefect::nonmanifold_edge: return "nonmanifold_edge";
    case InputDefect::nonmanifold_vertex: return "nonmanifold_vertex";
    case InputDefect::open_boundary: return "open_boundary";
    case InputDefect::inconsistent_orientation: return "inconsistent_orientation";
    case InputDefect::wrong_orientation: return "wrong_orientation";
    case InputDefect::self_intersection: return "self_intersection";
    case InputDefect::bad_features: return "bad_features";
    case InputDefect::count: break;
  }
  return "unknown";
}

int exit_code(InputDefect d) { return static_cast<int>(ExitCode::input_defect_base) + static_cast<int>(d); }

} // namespace curvetet

// extrude_one_sided: the layer machinery of the shell with one slab only.
#include "curvetet/core/error.hpp"
#include "curvetet/shell/extrusion.hpp"
#include "curvetet/shell/layer_growth.hpp"

#include <algorithm>
#include <limits>

namespace curvetet::shell {

OneSidedExtrusion extrude_one_sided(const mesh::SurfaceMesh& surface, Side side, const ExtrusionOptions& options) {
  if (surface.num_faces() == 0) throw Error(ExitCode::internal, "extrude_one_sided: empty surface");
  Shell s = flat_shell(surface);

  const auto dirs = extrusion_directions(surface, options.singular_dot);
  LayerGrowthSpec spec;
  spec.grow_bottom = side == Side::inward;
  spec.grow_top = side == Side::outward;
  const double diag = mesh::bbox_diagonal(surface.vertices);
  spec.target = absolute_length(options.target_thickness, options.target_thickness_abs, diag);
  spec.initial = std::min(spec.target, options.initial_thickness * diag);
  spec.max_rounds = options.max_rounds;
  spec.stop_requested = options.stop_requested;
  spec.direction.resize(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) {
    spec.direction[v] = dirs[v].direction;
    s.singular[v] = dirs[v].singular;
  }
  std::vector<double> length;
  const auto stats = grow_layer(s, spec, length);

  OneSidedExtrusion out;
  out.offset = side == Side::inward ? s.bottom : s.top;
  out.direction.resize(surface.num_vertices());
  const double sign = side == Side::inward ? -1.0 : 1.0;
  for (int v = 0; v < surface.num_vertices(); ++v) out.direction[v] = sign * spec.direction[v];
  out.length = length;
  out.singular = s.singular;
  out.rounds = stats.rounds;
  out.min_length = std::numeric_limits<double>::infinity();
  for (int v = 0; v < surface.num_vertices(); ++v) {
    if (s.singular[v]) continue;
    out.min_length = std::min(out.min_length, length[v]);
    out.max_length = std::max(out.max_length, length[v]);
  }
  if (!std::isfinite(out.min_length)) out.min_length = 0;
  return out;
}

} // namespace curvetet::shell

#include "curvetet/shell/coarsen.hpp"
#include "curvetet/shell/prism_geometry.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace curvetet::shell {

MapCheck check_map(const Shell& s, bool bijectivity) {
  MapCheck out;
  // Distance and consistency of every stored image.
  const int P = static_cast<int>(s.points.size());
  std::vector<double> dist(P, 0);
  std::vector<char> outside(P, 0);
  tbb::parallel_for(0, P, [&](int i) {
    const auto& p = s.points[i];
    if (p.image.prism < 0 || p.image.prism >= s.num_prisms()) {
      outside[i] = 1;
      dist[i] = std::numeric_limits<double>::infinity();
      return;
    }
    const PrismGeom g = prism_geom(s, p.image.prism);
    // Containment exact; the stored (u, v) must agree with a fresh double
    // projection (a consistency check of the bookkeeping, not a decision).
    const Vec3 bar = straight_point(s, i);
    const auto uv = project_in(g, bar, std::numeric_limits<double>::infinity());
    const bool snapped = i < static_cast<int>(s.features.on_edge.size()) && s.features.on_edge[i].a >= 0;
    outside[i] = (!snapped && !prism_contains(g, bar)) || !uv || std::abs((*uv)[0] - p.image.u) > 1e-9 || std::abs((*uv)[1] - p.image.v) > 1e-9;
    const Vec3 x = middle_point(s, p.image);
    dist[i] = (x - p.position).norm();
  });
  for (int i = 0; i < P; ++i) {
    out.points_outside += outside[i];
    if (dist[i] > out.max_distance || out.worst_point < 0) {
      out.max_distance = std::max(out.max_distance, dist[i]);
      if (dist[i] >= out.max_distance) out.worst_point = i;
    }
  }
  // Bijectivity: the images of the tracked faces tile each middle triangle,
  // decided in exact rationals.
  const int F = bijectivity ? s.num_prisms() : 0;
  const mesh::SurfaceMesh bar{s.straight.empty() ? s.input.vertices : s.straight, s.input.faces}; // M̄
  std::vector<ExactImageArea> area(F);
  tbb::parallel_for(0, F, [&](int f) { area[f] = exact_image_area_sum(prism_geom(s, f), bar, s.tracked[f]); });
  out.min_piece_area = std::numeric_limits<double>::infinity();
  for (int f = 0; f < F; ++f) {
    out.prisms_not_tiled += !area[f].tiles;
    out.prisms_folded += !area[f].positive;
    if (area[f].error > out.max_area_error || (!area[f].tiles && out.worst_prism < 0)) {
      out.max_area_error = area[f].error;
      out.worst_prism = f;
    }
    out.min_piece_area = std::min(out.min_piece_area, area[f].min_piece);
  }
  if (F == 0) out.min_piece_area = 0;
  return out;
}

} // namespace curvetet::shell

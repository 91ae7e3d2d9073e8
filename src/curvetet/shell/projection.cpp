#include "curvetet/shell/projection.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/prism_geometry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace curvetet::shell {

Projector::Projector(const Shell& s) : s_(s), trackers_(input_trackers(s)) {}

std::optional<MapPoint> Projector::project_in_prism(int prism, const Vec3& p, double tol) const {
  const auto uv = project_in(prism_geom(s_, prism), p, tol);
  if (!uv) return std::nullopt;
  return MapPoint{prism, (*uv)[0], (*uv)[1]};
}

MapPoint Projector::project(const Vec3& p, int input_face) const {
  // The deepest containing prism: robust on shared boundaries.
  std::optional<MapPoint> best;
  double best_depth = -std::numeric_limits<double>::infinity();
  for (int f : trackers_[input_face]) {
    auto m = project_in_prism(f, p, std::numeric_limits<double>::infinity());
    if (!m) continue;
    const double depth = std::min({m->u, m->v, 1 - m->u - m->v});
    if (depth > best_depth) {
      best_depth = depth;
      best = m;
    }
  }
  if (best && project_in_prism(best->prism, p)) return *best;
  throw Error(ExitCode::internal, fmt::format("shell projection: point ({}, {}, {}) of input face {} lies in no prism "
                                              "tracking it",
                                              p[0], p[1], p[2], input_face));
}

std::optional<Vec3> Projector::unproject(const MapPoint& m, int* input_face) const {
  const PrismGeom g = prism_geom(s_, m.prism);
  double best = -std::numeric_limits<double>::infinity();
  std::optional<Vec3> best_point;
  for (int it : s_.tracked[m.prism]) {
    const auto tri = straight_triangle(s_, it);
    double depth = 0;
    auto hit = fiber_hit(g, m.u, m.v, tri[0], tri[1], tri[2], &depth);
    if (hit && depth > best) {
      best = depth;
      best_point = hit;
      if (input_face) *input_face = it;
    }
  }
  return best_point;
}

Vec3 Projector::middle_point(const MapPoint& m) const {
  const Tri& f = s_.faces[m.prism];
  return (1 - m.u - m.v) * s_.middle[f[0]] + m.u * s_.middle[f[1]] + m.v * s_.middle[f[2]];
}

int Projector::remap_points(Shell& s) const {
  int failed = 0;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    auto& p = s.points[i];
    try {
      p.image = project(straight_point(s, static_cast<int>(i)), p.input_face);
    } catch (const Error&) {
      ++failed;
    }
  }
  return failed;
}

} // namespace curvetet::shell

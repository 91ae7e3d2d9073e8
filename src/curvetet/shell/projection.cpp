#include "curvetet/shell/projection.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/prism_tets.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace curvetet::shell {

namespace {

constexpr Slab kSlabs[2] = {Slab::bottom, Slab::top};

struct TetFrame {
  Vec3 p[4]; // physical corners
  Vec3 r[4]; // reference corners (u, v, w)
};

TetFrame frame(const Shell& s, Slab slab, const Tri& f, const SlabTet& tet) {
  TetFrame t;
  for (int i = 0; i < 4; ++i) {
    const int c = tet.corners[i];
    t.p[i] = c < 3 ? slab_lower(s, slab, f[c]) : slab_upper(s, slab, f[c - 3]);
    const auto rc = reference_corner(c);
    t.r[i] = Vec3(rc[0], rc[1], rc[2]);
  }
  return t;
}

// Barycentric coordinates of x in the tet with corners q[0..3].
Eigen::Vector4d barycentric(const Vec3 q[4], const Vec3& x) {
  Eigen::Matrix3d A;
  A << q[1] - q[0], q[2] - q[0], q[3] - q[0];
  const Vec3 y = A.partialPivLu().solve(x - q[0]);
  return Eigen::Vector4d(1 - y.sum(), y[0], y[1], y[2]);
}

} // namespace

Projector::Projector(const Shell& s) : s_(s), trackers_(input_trackers(s)) {}

std::optional<MapPoint> Projector::project_in_prism(int prism, const Vec3& p, double tol) const {
  const Tri& f = s_.faces[prism];
  double best = -std::numeric_limits<double>::infinity();
  Vec3 best_ref;
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(f)) {
      if (zero_pillar(s_, slab, f[tet.pillar])) continue;
      const TetFrame t = frame(s_, slab, f, tet);
      const Eigen::Vector4d l = barycentric(t.p, p);
      const double depth = l.minCoeff();
      if (depth > best) {
        best = depth;
        best_ref = l[0] * t.r[0] + l[1] * t.r[1] + l[2] * t.r[2] + l[3] * t.r[3];
      }
    }
  if (!(best >= -tol)) return std::nullopt;
  return MapPoint{prism, best_ref[0], best_ref[1]};
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
  const Tri& f = s_.faces[m.prism];
  double best = -std::numeric_limits<double>::infinity();
  Vec3 best_point;
  int best_face = -1;
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(f)) {
      if (zero_pillar(s_, slab, f[tet.pillar])) continue;
      const TetFrame t = frame(s_, slab, f, tet);
      // Reference barycentrics along the vertical line: l(w) = l0 + w dl.
      const Eigen::Vector4d l0 = barycentric(t.r, Vec3(m.u, m.v, 0));
      const Eigen::Vector4d dl = barycentric(t.r, Vec3(m.u, m.v, 1)) - l0;
      double w0 = 0, w1 = 1;
      for (int i = 0; i < 4; ++i) {
        if (dl[i] > 0) w0 = std::max(w0, -l0[i] / dl[i]);
        else if (dl[i] < 0) w1 = std::min(w1, -l0[i] / dl[i]);
        else if (l0[i] < -1e-12) w1 = -1;
      }
      if (w0 > w1 + 1e-12) continue;
      auto at = [&](double w) {
        const Eigen::Vector4d l = l0 + w * dl;
        return Vec3(l[0] * t.p[0] + l[1] * t.p[1] + l[2] * t.p[2] + l[3] * t.p[3]);
      };
      const Vec3 x0 = at(w0), x1 = at(w1);
      for (int it : s_.tracked[m.prism]) {
        const auto& tri = s_.input.faces[it];
        const Vec3 &a = s_.input.vertices[tri[0]], &b = s_.input.vertices[tri[1]], &c = s_.input.vertices[tri[2]];
        const Vec3 n = (b - a).cross(c - a);
        const double s0 = n.dot(x0 - a), s1 = n.dot(x1 - a);
        Vec3 x;
        if (s0 == s1) {
          // A fiber reduced to a point (over a pinched pillar) or running in
          // the plane: a hit only if that point is on the plane (to rounding).
          if (std::abs(s0) > 1e-12 * std::sqrt(n.squaredNorm()) * (x0 - a).norm()) continue;
          x = x0;
        } else {
          // Crossing parameter; ends on the plane up to rounding count.
          const double tau = s0 / (s0 - s1);
          if (!(tau >= -1e-9 && tau <= 1 + 1e-9)) continue;
          x = x0 + std::clamp(tau, 0.0, 1.0) * (x1 - x0);
        }
        // Barycentrics of x in the input face (x is on its plane).
        const double area = n.squaredNorm();
        const double lb = n.dot((x - a).cross(c - a)) / area, lc = n.dot((b - a).cross(x - a)) / area;
        const double depth = std::min({1 - lb - lc, lb, lc});
        if (depth > best) {
          best = depth;
          best_point = x;
          best_face = it;
        }
      }
    }
  if (!(best >= -1e-9)) return std::nullopt;
  if (input_face) *input_face = best_face;
  return best_point;
}

Vec3 Projector::middle_point(const MapPoint& m) const {
  const Tri& f = s_.faces[m.prism];
  return (1 - m.u - m.v) * s_.middle[f[0]] + m.u * s_.middle[f[1]] + m.v * s_.middle[f[2]];
}

int Projector::remap_points(Shell& s) const {
  int failed = 0;
  for (auto& p : s.points) {
    try {
      p.image = project(p.position, p.input_face);
    } catch (const Error&) {
      ++failed;
    }
  }
  return failed;
}

} // namespace curvetet::shell

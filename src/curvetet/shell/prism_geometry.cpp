#include "curvetet/shell/prism_geometry.hpp"

#include "curvetet/geometry/predicates.hpp"
#include "curvetet/shell/exact_dot.hpp"
#include "curvetet/shell/prism_tets.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace curvetet::shell {

using geometry::orient3d;

namespace {

constexpr Slab kSlabs[2] = {Slab::bottom, Slab::top};

bool point_in_closed_tet(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return orient3d(p, b, c, d) >= 0 && orient3d(a, p, c, d) >= 0 && orient3d(a, b, p, d) >= 0 &&
         orient3d(a, b, c, p) >= 0;
}

// Exact: closed triangle meets closed positive tet.
bool triangle_meets_tet(const Vec3* tri[3], const Vec3* v[4]) {
  for (int i = 0; i < 3; ++i)
    if (point_in_closed_tet(*tri[i], *v[0], *v[1], *v[2], *v[3])) return true;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (geometry::segment_triangle_intersect(*v[i], *v[j], *tri[0], *tri[1], *tri[2])) return true;
  static const int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (const auto& fc : faces)
    for (int e = 0; e < 3; ++e)
      if (geometry::segment_triangle_intersect(*tri[e], *tri[(e + 1) % 3], *v[fc[0]], *v[fc[1]], *v[fc[2]]))
        return true;
  return false;
}

struct TetFrame {
  Vec3 p[4], r[4];
};

TetFrame frame(const PrismGeom& g, Slab slab, const SlabTet& tet) {
  TetFrame t;
  for (int i = 0; i < 4; ++i) {
    const int c = tet.corners[i];
    t.p[i] = g.corner(slab, c);
    const auto rc = reference_corner(c);
    // The two slabs stack: bottom slab w in [0, 1], top slab w in [1, 2].
    t.r[i] = Vec3(rc[0], rc[1], rc[2] + (slab == Slab::top ? 1.0 : 0.0));
  }
  return t;
}

Eigen::Vector4d barycentric(const Vec3 q[4], const Vec3& x) {
  Eigen::Matrix3d A;
  A << q[1] - q[0], q[2] - q[0], q[3] - q[0];
  const Vec3 y = A.partialPivLu().solve(x - q[0]);
  return Eigen::Vector4d(1 - y.sum(), y[0], y[1], y[2]);
}

} // namespace

PrismGeom prism_geom(const Shell& s, int prism) {
  PrismGeom g;
  g.ids = s.faces[prism];
  for (int k = 0; k < 3; ++k) {
    g.bottom[k] = s.bottom[g.ids[k]];
    g.middle[k] = s.middle[g.ids[k]];
    g.top[k] = s.top[g.ids[k]];
  }
  return g;
}

bool positive(const PrismGeom& g) {
  for (Slab slab : kSlabs)
    for (const auto& tet : all_slab_tets()) {
      if (g.zero_pillar(slab, tet.pillar)) continue;
      const auto& c = tet.corners;
      if (orient3d(g.corner(slab, c[0]), g.corner(slab, c[1]), g.corner(slab, c[2]), g.corner(slab, c[3])) <= 0)
        return false;
    }
  return true;
}

bool triangle_meets_prism(const PrismGeom& g, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3* tri[3] = {&a, &b, &c};
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(g.ids)) {
      if (g.zero_pillar(slab, tet.pillar)) continue;
      const auto& q = tet.corners;
      const Vec3* v[4] = {&g.corner(slab, q[0]), &g.corner(slab, q[1]), &g.corner(slab, q[2]), &g.corner(slab, q[3])};
      if (triangle_meets_tet(tri, v)) return true;
    }
  return false;
}

bool section_condition(const PrismGeom& g, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3* tri[3] = {&a, &b, &c};
  for (Slab slab : kSlabs)
    for (int k = 0; k < 3; ++k) {
      if (g.zero_pillar(slab, k)) continue;
      if (normal_dot_sign(a, b, c, g.lower(slab, k), g.upper(slab, k)) > 0) continue;
      for (const auto& tet : all_slab_tets()) {
        if (tet.pillar != k) continue;
        const auto& q = tet.corners;
        const Vec3* v[4] = {&g.corner(slab, q[0]), &g.corner(slab, q[1]), &g.corner(slab, q[2]),
                            &g.corner(slab, q[3])};
        if (orient3d(*v[0], *v[1], *v[2], *v[3]) <= 0) return false; // defined on positive prisms only
        if (triangle_meets_tet(tri, v)) return false;
      }
    }
  return true;
}

std::optional<std::array<double, 2>> project_in(const PrismGeom& g, const Vec3& p, double tol, double* depth) {
  double best = -std::numeric_limits<double>::infinity();
  Vec3 best_ref = Vec3::Zero();
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(g.ids)) {
      if (g.zero_pillar(slab, tet.pillar)) continue;
      const TetFrame t = frame(g, slab, tet);
      const Eigen::Vector4d l = barycentric(t.p, p);
      const double d = l.minCoeff();
      if (d > best) {
        best = d;
        best_ref = l[0] * t.r[0] + l[1] * t.r[1] + l[2] * t.r[2] + l[3] * t.r[3];
      }
    }
  if (depth) *depth = best;
  if (!(best >= -tol)) return std::nullopt;
  return std::array<double, 2>{best_ref[0], best_ref[1]};
}

std::optional<Vec3> fiber_hit(const PrismGeom& g, double u, double v, const Vec3& a, const Vec3& b, const Vec3& c,
                              double* depth) {
  const Vec3 n = (b - a).cross(c - a);
  const double area = n.squaredNorm();
  double best = -std::numeric_limits<double>::infinity();
  Vec3 best_point = Vec3::Zero();
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(g.ids)) {
      if (g.zero_pillar(slab, tet.pillar)) continue;
      const TetFrame t = frame(g, slab, tet);
      const double w_lo = slab == Slab::top ? 1.0 : 0.0;
      const Eigen::Vector4d l0 = barycentric(t.r, Vec3(u, v, w_lo));
      const Eigen::Vector4d dl = barycentric(t.r, Vec3(u, v, w_lo + 1)) - l0;
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
      const double s0 = n.dot(x0 - a), s1 = n.dot(x1 - a);
      Vec3 x;
      if (s0 == s1) {
        // A fiber reduced to a point (over a pinched pillar) or running in
        // the plane: a hit only if that point is on the plane (to rounding).
        if (std::abs(s0) > 1e-12 * std::sqrt(area) * (x0 - a).norm()) continue;
        x = x0;
      } else {
        // Crossing parameter; ends on the plane up to rounding count.
        const double tau = s0 / (s0 - s1);
        if (!(tau >= -1e-9 && tau <= 1 + 1e-9)) continue;
        x = x0 + std::clamp(tau, 0.0, 1.0) * (x1 - x0);
      }
      const double lb = n.dot((x - a).cross(c - a)) / area, lc = n.dot((b - a).cross(x - a)) / area;
      const double d = std::min({1 - lb - lc, lb, lc});
      if (d > best) {
        best = d;
        best_point = x;
      }
    }
  if (depth) *depth = best;
  if (!(best >= -1e-9)) return std::nullopt;
  return best_point;
}

namespace {

// Clips a convex polygon (u, v) to the reference triangle u, v >= 0,
// u + v <= 1 and returns twice its signed area.
double clipped_reference_area(std::vector<std::array<double, 2>> poly) {
  for (int i = 0; i < 3 && !poly.empty(); ++i) {
    auto value = [&](const std::array<double, 2>& p) { return i == 0 ? p[0] : i == 1 ? p[1] : 1 - p[0] - p[1]; };
    std::vector<std::array<double, 2>> next;
    for (std::size_t j = 0; j < poly.size(); ++j) {
      const auto& P = poly[j];
      const auto& Q = poly[(j + 1) % poly.size()];
      const double p = value(P), q = value(Q);
      if (p >= 0) next.push_back(P);
      if ((p >= 0) != (q >= 0)) {
        const double t = p / (p - q);
        next.push_back({P[0] + t * (Q[0] - P[0]), P[1] + t * (Q[1] - P[1])});
      }
    }
    poly = std::move(next);
  }
  double twice = 0;
  for (std::size_t j = 0; j < poly.size(); ++j) {
    const auto& p = poly[j];
    const auto& q = poly[(j + 1) % poly.size()];
    twice += p[0] * q[1] - p[1] * q[0];
  }
  return twice;
}

} // namespace

ImageArea image_area(const PrismGeom& g, const Vec3& a, const Vec3& b, const Vec3& c) {
  ImageArea out;
  const auto& m = g.middle;
  // A triangle lying in the middle triangle's plane (e.g. the initial shell,
  // where middle = input, or a flat region): the fibers start on it, so its
  // image is its own barycentric shadow on the middle triangle.
  // "In the plane" up to rounding (1e-12 of the triangle's size): such a
  // triangle straddles the two slabs by rounding noise, so clipping it to
  // the slabs' tets would lose or double-count slivers of it.
  const Vec3 n = (m[1] - m[0]).cross(m[2] - m[0]);
  const double scale = std::max({(m[1] - m[0]).norm(), (m[2] - m[1]).norm(), (m[0] - m[2]).norm()});
  auto off_plane = [&](const Vec3& x) { return std::abs(n.normalized().dot(x - m[0])); };
  if (n.norm() > 0 && off_plane(a) <= 1e-12 * scale && off_plane(b) <= 1e-12 * scale &&
      off_plane(c) <= 1e-12 * scale) {
    const Vec3 e1 = m[1] - m[0], e2 = m[2] - m[0];
    Eigen::Matrix<double, 3, 2> E;
    E << e1, e2;
    const Eigen::Matrix2d G = E.transpose() * E;
    std::vector<std::array<double, 2>> poly;
    for (const Vec3* x : {&a, &b, &c}) {
      const Eigen::Vector2d uv = G.ldlt().solve(E.transpose() * (*x - m[0]));
      poly.push_back({uv[0], uv[1]});
    }
    out.area = out.min_piece = clipped_reference_area(poly);
    return out;
  }
  out.min_piece = std::numeric_limits<double>::infinity();
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(g.ids)) {
      if (g.zero_pillar(slab, tet.pillar)) continue;
      const TetFrame t = frame(g, slab, tet);
      // Clip the triangle to the tet in the tet's barycentric coordinates.
      std::vector<Eigen::Vector4d> poly = {barycentric(t.p, a), barycentric(t.p, b), barycentric(t.p, c)};
      for (int i = 0; i < 4 && !poly.empty(); ++i) {
        std::vector<Eigen::Vector4d> next;
        for (std::size_t j = 0; j < poly.size(); ++j) {
          const auto& P = poly[j];
          const auto& Q = poly[(j + 1) % poly.size()];
          const bool pin = P[i] >= 0, qin = Q[i] >= 0;
          if (pin) next.push_back(P);
          if (pin != qin) next.push_back(P + (Q - P) * (P[i] / (P[i] - Q[i])));
        }
        poly = std::move(next);
      }
      if (poly.size() < 3) continue;
      double twice = 0;
      std::vector<std::array<double, 2>> uv;
      for (const auto& l : poly) {
        const Vec3 r = l[0] * t.r[0] + l[1] * t.r[1] + l[2] * t.r[2] + l[3] * t.r[3];
        uv.push_back({r[0], r[1]});
      }
      for (std::size_t j = 0; j < uv.size(); ++j) {
        const auto& p = uv[j];
        const auto& q = uv[(j + 1) % uv.size()];
        twice += p[0] * q[1] - p[1] * q[0];
      }
      // The reference middle triangle has area 1/2: twice the area = units.
      out.area += twice;
      out.min_piece = std::min(out.min_piece, twice);
    }
  if (out.min_piece == std::numeric_limits<double>::infinity()) out.min_piece = 0;
  return out;
}

} // namespace curvetet::shell

#include "curvetet/shell/prism_geometry.hpp"

#include "curvetet/geometry/predicates.hpp"
#include "curvetet/shell/exact_dot.hpp"
#include "curvetet/shell/prism_tets.hpp"
#include "curvetet/shell/tet_contact.hpp"

#include <Eigen/Dense>
#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <vector>

namespace curvetet::shell {

using geometry::orient3d;

namespace {

constexpr Slab kSlabs[2] = {Slab::bottom, Slab::top};

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

bool prism_contains(const PrismGeom& g, const Vec3& p) {
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(g.ids)) {
      if (g.zero_pillar(slab, tet.pillar)) continue;
      const auto& q = tet.corners;
      const Vec3 v[4] = {g.corner(slab, q[0]), g.corner(slab, q[1]), g.corner(slab, q[2]), g.corner(slab, q[3])};
      if (orient3d(p, v[1], v[2], v[3]) >= 0 && orient3d(v[0], p, v[2], v[3]) >= 0 && orient3d(v[0], v[1], p, v[3]) >= 0 &&
          orient3d(v[0], v[1], v[2], p) >= 0)
        return true;
    }
  return false;
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
        const auto allowed = section_allowed_corners(tet, slab == Slab::bottom);
        if (triangle_meets_tet_outside(tri, v, allowed.data())) return false;
      }
    }
  return true;
}

std::optional<std::array<double, 2>> project_in(const PrismGeom& g, const Vec3& p, double tol, double* depth) {
  return PrismProjection(g)(p, tol, depth);
}

PrismProjection::PrismProjection(const PrismGeom& g) : middle_(g.middle) {
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(g.ids)) {
      if (g.zero_pillar(slab, tet.pillar)) continue;
      const TetFrame t = frame(g, slab, tet);
      Tet& out = tets_[count_++];
      out.origin = t.p[0];
      for (int i = 0; i < 4; ++i) out.reference[i] = t.r[i];
      Eigen::Matrix3d A;
      A << t.p[1] - t.p[0], t.p[2] - t.p[0], t.p[3] - t.p[0];
      out.lu.compute(A);
    }
}

std::optional<std::array<double, 2>> PrismProjection::operator()(const Vec3& p, double tol, double* depth) const {
  // A middle vertex is the foot of its own fiber: its image is that corner
  // exactly (feature corners land on their output vertex, not 1e-32 beside).
  for (int k = 0; k < 3; ++k)
    if (p == middle_[k]) {
      if (depth) *depth = 0;
      return std::array<double, 2>{k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0};
    }
  double best = -std::numeric_limits<double>::infinity();
  Vec3 best_ref = Vec3::Zero();
  for (int i = 0; i < count_; ++i) {
    const Tet& t = tets_[i];
    const Vec3 y = t.lu.solve(Vec3(p - t.origin));
    const Eigen::Vector4d l(1 - y.sum(), y[0], y[1], y[2]);
    const double d = l.minCoeff();
    if (d > best) {
      best = d;
      best_ref = l[0] * t.reference[0] + l[1] * t.reference[1] + l[2] * t.reference[2] + l[3] * t.reference[3];
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

// One canonical tet of a prism, ready for image measures.
struct ImageTet {
  TetFrame t;
  double volume; // 6 x signed volume, relative error <= 1e-12
};

std::vector<ImageTet> image_tets(const PrismGeom& g) {
  std::vector<ImageTet> out;
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(g.ids)) {
      if (g.zero_pillar(slab, tet.pillar)) continue;
      ImageTet it{frame(g, slab, tet), 0};
      it.volume = orient3d_value(it.t.p[0], it.t.p[1], it.t.p[2], it.t.p[3]);
      if (it.volume > 0) out.push_back(it); // only defined on positive prisms
    }
  return out;
}

// Barycentric coordinates of x in the tet as volume ratios, each with a
// small relative error: a point 1e-19 off a tet face must not land on the
// wrong side of it, or the clip cuts a sliver of arbitrary size along an
// edge lying in that face.
Eigen::Vector4d accurate_barycentric(const ImageTet& it, const Vec3& x) {
  Eigen::Vector4d l;
  for (int i = 0; i < 4; ++i) {
    Vec3 q[4] = {it.t.p[0], it.t.p[1], it.t.p[2], it.t.p[3]};
    q[i] = x;
    l[i] = orient3d_value(q[0], q[1], q[2], q[3]) / it.volume;
  }
  return l;
}

// Twice the (u, v) area of the image of (a, b, c) clipped to the tet, given
// the corners' barycentric coordinates; nullopt when the piece is empty or
// belongs to the neighbouring tet.
std::optional<double> tet_piece(const ImageTet& it, const Vec3& a, const Vec3& b, const Vec3& c,
                                std::vector<Eigen::Vector4d> poly) {
  // A triangle lying exactly in the plane of face i (the middle triangle of
  // a flat region, an inner face of the split) is in both closed tets
  // sharing that face; it belongs to the one on its positive side (as if
  // pushed along its normal), so it is counted once.
  for (int i = 0; i < 4; ++i)
    if (poly[0][i] == 0 && poly[1][i] == 0 && poly[2][i] == 0 && orient3d(a, b, c, it.t.p[i]) < 0)
      return std::nullopt;
  for (int i = 0; i < 4 && !poly.empty(); ++i) {
    std::vector<Eigen::Vector4d> next;
    for (std::size_t j = 0; j < poly.size(); ++j) {
      const auto& P = poly[j];
      const auto& Q = poly[(j + 1) % poly.size()];
      const bool pin = P[i] >= 0, qin = Q[i] >= 0;
      if (pin) next.push_back(P);
      if (pin != qin) {
        Eigen::Vector4d X = P + (Q - P) * (P[i] / (P[i] - Q[i]));
        X[i] = 0; // on the plane, exactly
        next.push_back(X);
      }
    }
    poly = std::move(next);
  }
  if (poly.size() < 3) return std::nullopt;
  std::vector<std::array<double, 2>> uv;
  for (const auto& l : poly) {
    const Vec3 r = l[0] * it.t.r[0] + l[1] * it.t.r[1] + l[2] * it.t.r[2] + l[3] * it.t.r[3];
    uv.push_back({r[0], r[1]});
  }
  double twice = 0;
  for (std::size_t j = 0; j < uv.size(); ++j) {
    const auto& p = uv[j];
    const auto& q = uv[(j + 1) % uv.size()];
    twice += p[0] * q[1] - p[1] * q[0];
  }
  // The reference middle triangle has area 1/2: twice the area = units.
  return twice;
}

void add_piece(ImageArea& out, std::optional<double> twice) {
  if (!twice) return;
  out.area += *twice;
  out.min_piece = std::min(out.min_piece, *twice);
}

} // namespace

ImageArea image_area(const PrismGeom& g, const Vec3& a, const Vec3& b, const Vec3& c) {
  ImageArea out;
  out.min_piece = std::numeric_limits<double>::infinity();
  for (const auto& it : image_tets(g))
    add_piece(out, tet_piece(it, a, b, c, {accurate_barycentric(it, a), accurate_barycentric(it, b),
                                           accurate_barycentric(it, c)}));
  if (out.min_piece == std::numeric_limits<double>::infinity()) out.min_piece = 0;
  return out;
}

ImageArea image_area_sum(const PrismGeom& g, const mesh::SurfaceMesh& input, std::span<const int> faces) {
  ImageArea out;
  out.min_piece = std::numeric_limits<double>::infinity();
  std::vector<int> verts;
  for (int f : faces)
    for (int v : input.faces[f]) verts.push_back(v);
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  auto local = [&](int v) { return std::lower_bound(verts.begin(), verts.end(), v) - verts.begin(); };
  for (const auto& it : image_tets(g)) {
    std::vector<Eigen::Vector4d> bary(verts.size());
    for (std::size_t i = 0; i < verts.size(); ++i) bary[i] = accurate_barycentric(it, input.vertices[verts[i]]);
    for (int f : faces) {
      const auto& t = input.faces[f];
      // Entirely outside one face plane (the common case): nothing to clip.
      bool outside = false;
      for (int i = 0; i < 4 && !outside; ++i)
        outside = bary[local(t[0])][i] < 0 && bary[local(t[1])][i] < 0 && bary[local(t[2])][i] < 0;
      if (outside) continue;
      add_piece(out, tet_piece(it, input.vertices[t[0]], input.vertices[t[1]], input.vertices[t[2]],
                               {bary[local(t[0])], bary[local(t[1])], bary[local(t[2])]}));
    }
  }
  if (out.min_piece == std::numeric_limits<double>::infinity()) out.min_piece = 0;
  return out;
}

namespace {

using Integer = mpz_class;
using Rational = mpq_class;
using IntPoint = std::array<Integer, 3>;
// Barycentric coordinates up to a positive factor (their sum): the clip
// below is homogeneous in them, so it needs neither division nor gcd.
using Homogeneous = std::array<Integer, 4>;

// Doubles as integers on one common grid 2^E (E = the smallest ulp among
// them): exact, and every determinant below is an integer.
struct IntegerGrid {
  int exponent = 0;
  explicit IntegerGrid(const std::vector<Vec3>& points) {
    exponent = std::numeric_limits<int>::max();
    for (const auto& p : points)
      for (int i = 0; i < 3; ++i)
        if (p[i] != 0) {
          int e = 0;
          std::frexp(p[i], &e);
          exponent = std::min(exponent, e - 53);
        }
    if (exponent == std::numeric_limits<int>::max()) exponent = 0;
  }
  IntPoint operator()(const Vec3& p) const {
    IntPoint out;
    for (int i = 0; i < 3; ++i) {
      int e = 0;
      const double f = std::frexp(p[i], &e); // p = f 2^e, f 2^53 an integer
      out[i] = Integer(std::ldexp(f, 53));
      out[i] <<= static_cast<unsigned long>(e - 53 - exponent);
    }
    return out;
  }
};

// det[b - a, c - a, d - a].
Integer orient(const IntPoint& a, const IntPoint& b, const IntPoint& c, const IntPoint& d) {
  Integer m[3][3];
  for (int i = 0; i < 3; ++i) {
    m[0][i] = b[i] - a[i];
    m[1][i] = c[i] - a[i];
    m[2][i] = d[i] - a[i];
  }
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// Barycentric coordinates of x times the tet's volume (positive).
Homogeneous scaled_barycentric(const std::array<IntPoint, 4>& tet, const IntPoint& x) {
  Homogeneous l;
  for (int i = 0; i < 4; ++i) {
    auto q = tet;
    q[i] = x;
    l[i] = orient(q[0], q[1], q[2], q[3]);
  }
  return l;
}

// tet_piece in exact arithmetic: twice the (u, v) area of the clipped image.
// An edge leaving face plane i from P (P_i >= 0) to Q (Q_i < 0) crosses it
// at P_i Q - Q_i P: coordinate i zero, weight positive.
std::optional<Rational> exact_piece(const TetFrame& t, const Vec3& a, const Vec3& b, const Vec3& c,
                                    std::vector<Homogeneous> poly) {
  for (int i = 0; i < 4; ++i)
    if (sgn(poly[0][i]) == 0 && sgn(poly[1][i]) == 0 && sgn(poly[2][i]) == 0 && orient3d(a, b, c, t.p[i]) < 0)
      return std::nullopt;
  for (int i = 0; i < 4 && !poly.empty(); ++i) {
    std::vector<Homogeneous> next;
    for (std::size_t j = 0; j < poly.size(); ++j) {
      const auto& P = poly[j];
      const auto& Q = poly[(j + 1) % poly.size()];
      const bool pin = sgn(P[i]) >= 0, qin = sgn(Q[i]) >= 0;
      if (pin) next.push_back(P);
      if (pin != qin) {
        const auto& [in, out] = pin ? std::tie(P, Q) : std::tie(Q, P);
        Homogeneous X;
        for (int k = 0; k < 4; ++k) X[k] = in[i] * out[k] - out[i] * in[k];
        next.push_back(std::move(X));
      }
    }
    poly = std::move(next);
  }
  if (poly.size() < 3) return std::nullopt;
  // (u, v) = (A, B) / W per vertex, the reference corners' coordinates small integers.
  struct Projected {
    Integer A, B, W;
  };
  std::vector<Projected> uv;
  for (const auto& l : poly) {
    Projected r{0, 0, 0};
    for (int k = 0; k < 4; ++k) {
      r.A += l[k] * static_cast<long>(t.r[k][0]);
      r.B += l[k] * static_cast<long>(t.r[k][1]);
      r.W += l[k];
    }
    uv.push_back(std::move(r));
  }
  Rational twice = 0;
  for (std::size_t j = 0; j < uv.size(); ++j) {
    const auto& p = uv[j];
    const auto& q = uv[(j + 1) % uv.size()];
    Rational term(p.A * q.B - p.B * q.A, p.W * q.W);
    term.canonicalize();
    twice += term;
  }
  return twice;
}

} // namespace

ExactImageArea exact_image_area_sum(const PrismGeom& g, const mesh::SurfaceMesh& input, std::span<const int> faces) {
  std::vector<int> verts;
  for (int f : faces)
    for (int v : input.faces[f]) verts.push_back(v);
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  auto local = [&](int v) { return std::lower_bound(verts.begin(), verts.end(), v) - verts.begin(); };
  std::vector<TetFrame> tets;
  for (Slab slab : kSlabs)
    for (const auto& tet : canonical_split(g.ids))
      if (!g.zero_pillar(slab, tet.pillar)) tets.push_back(frame(g, slab, tet));
  std::vector<Vec3> all;
  for (const auto& t : tets) all.insert(all.end(), t.p, t.p + 4);
  for (int v : verts) all.push_back(input.vertices[v]);
  const IntegerGrid grid(all);
  std::vector<IntPoint> vert_int;
  for (int v : verts) vert_int.push_back(grid(input.vertices[v]));

  Rational area = 0;
  ExactImageArea out;
  out.positive = true;
  out.min_piece = std::numeric_limits<double>::infinity();
  for (const auto& t : tets) {
    const std::array<IntPoint, 4> tet{grid(t.p[0]), grid(t.p[1]), grid(t.p[2]), grid(t.p[3])};
    if (sgn(orient(tet[0], tet[1], tet[2], tet[3])) <= 0) continue; // only defined on positive prisms
    // Exact signs of the barycentric coordinates first (filtered
    // predicates): a face wholly outside one face plane, the common case,
    // needs no big integers.
    std::vector<std::array<int, 4>> sign(verts.size());
    for (std::size_t k = 0; k < verts.size(); ++k)
      for (int i = 0; i < 4; ++i) {
        Vec3 q[4] = {t.p[0], t.p[1], t.p[2], t.p[3]};
        q[i] = input.vertices[verts[k]];
        sign[k][i] = orient3d(q[0], q[1], q[2], q[3]);
      }
    std::vector<std::optional<Homogeneous>> bary(verts.size());
    auto exact = [&](int v) -> const Homogeneous& {
      auto& b = bary[local(v)];
      if (!b) b = scaled_barycentric(tet, vert_int[local(v)]);
      return *b;
    };
    for (int f : faces) {
      const auto& tri = input.faces[f];
      bool outside = false;
      for (int i = 0; i < 4 && !outside; ++i)
        outside = sign[local(tri[0])][i] < 0 && sign[local(tri[1])][i] < 0 && sign[local(tri[2])][i] < 0;
      if (outside) continue;
      const Vec3 &a = input.vertices[tri[0]], &b = input.vertices[tri[1]], &c = input.vertices[tri[2]];
      const auto piece = exact_piece(t, a, b, c, {exact(tri[0]), exact(tri[1]), exact(tri[2])});
      if (!piece) continue;
      area += *piece;
      out.positive = out.positive && sgn(*piece) >= 0;
      out.min_piece = std::min(out.min_piece, piece->get_d());
    }
  }
  if (out.min_piece == std::numeric_limits<double>::infinity()) out.min_piece = 0;
  out.tiles = cmp(area, 1) == 0;
  out.error = Rational(abs(area - 1)).get_d();
  return out;
}

} // namespace curvetet::shell

#include "curvetet/check/patch_separation.hpp"

#include "curvetet/highorder/simplex_lattice.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace curvetet::check {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
constexpr double kU = std::numeric_limits<double>::epsilon() / 2; // unit roundoff
constexpr double kInf = std::numeric_limits<double>::infinity();

int orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  return static_cast<int>(CGAL::orientation(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y()),
                                            K::Point_2(c.x(), c.y())));
}

// Σ |ν_i| (|p_i| + |x_i|): the scale of the rounding of ν · (p - x), whose
// double evaluation (a subtraction, a product and a sum per coordinate)
// errs by at most γ4 times it.
double dot_scale(const Vec3& nu, const Vec3& p, const Vec3& x) {
  return (nu.cwiseAbs().array() * (p.cwiseAbs() + x.cwiseAbs()).array()).sum();
}

Vec3 corner_normal(const BezierPatch& p) {
  return (p.corner(1) - p.corner(0)).cross(p.corner(2) - p.corner(0));
}

// Two vectors spanning the plane normal to d, with (e1, e2, d) right-handed:
// the projection keeps the orientation of a piece whose normal has n · d > 0.
// Any linear map would do for the proof; these keep the layout well scaled.
std::array<Vec3, 2> plane_basis(const Vec3& d) {
  Eigen::Index axis = 0;
  d.cwiseAbs().minCoeff(&axis);
  const Vec3 e1 = d.cross(Vec3::Unit(axis)).normalized();
  return {e1, d.cross(e1)};
}

Vec2 project(const std::array<Vec3, 2>& e, const Vec3& x) { return {e[0].dot(x), e[1].dot(x)}; }

// Upper bound on sup ‖D(π ∘ F ∘ A⁻¹) - I‖ over the piece, A the affine map
// from its reference triangle to the layout triangle `at` (its corners'
// layout points): D(π∘F) is a convex combination of the matrices M_β of the
// derivative nets, so the sup is at most max_β ‖M_β - A‖ ‖A⁻¹‖, and
// ‖A⁻¹‖₂ ≤ ‖A‖_F / |det A|. Infinity when the layout triangle is not
// positively oriented. Rounding: the nets' entries err by δ (control radius
// r through n-fold differences, and the projection's dot product); A's
// entries are differences of doubles (relative u), det A adds 4u per term;
// norms and products add a few u relative, covered by the 8u factors.
double distortion(const BezierPatch& p, const std::array<Vec2, 3>& at, const std::array<Vec3, 2>& e) {
  Eigen::Matrix2d A;
  A.col(0) = at[1] - at[0];
  A.col(1) = at[2] - at[0];
  const double det = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0);
  const double det_low = det - 8 * kU * (std::abs(A(0, 0) * A(1, 1)) + std::abs(A(0, 1) * A(1, 0)));
  if (!(det_low > 0)) return kInf;
  const double a_norm = A.norm() * (1 + 8 * kU);
  const double inverse_norm = a_norm / det_low * (1 + 8 * kU);
  const int n = p.degree;
  const double e_l1 = std::max(e[0].lpNorm<1>(), e[1].lpNorm<1>());
  const double delta = e_l1 * 2 * n * (p.radius + 6 * kU * (p.max_abs + p.radius));
  const auto nets = derivative_nets(p);
  double worst = 0;
  for (std::size_t i = 0; i < nets[0].size(); ++i) {
    Eigen::Matrix2d M;
    M.col(0) = project(e, nets[0][i]);
    M.col(1) = project(e, nets[1][i]);
    worst = std::max(worst, (M - A).norm());
  }
  const double worst_up = worst * (1 + 8 * kU) + 2 * delta + 2 * kU * a_norm;
  return worst_up * inverse_norm * (1 + 8 * kU);
}

// Lower bound on sin(φ/2), φ the angle between w1 and w2: sin²(φ/2) =
// (1 - cos φ)/2, cos φ computed with an absolute error under 8u.
double half_angle_sine_low(const Vec2& w1, const Vec2& w2) {
  const double c = w1.dot(w2) / (w1.norm() * w2.norm());
  const double s2 = (1 - c - 8 * kU) / 2;
  return s2 > 0 ? std::sqrt(s2) * (1 - 4 * kU) : 0;
}

// A ν maximizing min_k ν · w_k over |ν_i| ≤ 1 (CGAL's exact linear
// programming): a point deep inside the dual cone of the directions w, also
// when they are coplanar or their gap is a few 1e-4 rad. Zero when the
// optimum is not positive (the cones overlap).
Vec3 deepest_separator(const std::vector<Vec3>& w) {
  CGAL::Quadratic_program<double> lp(CGAL::LARGER, false, 0, false, 0);
  for (int k = 0; k < static_cast<int>(w.size()); ++k) {
    for (int i = 0; i < 3; ++i) lp.set_a(i, k, w[k][i]);
    lp.set_a(3, k, -1.0);
    lp.set_b(k, 0.0);
  }
  for (int i = 0; i < 3; ++i) {
    lp.set_l(i, true, -1.0);
    lp.set_u(i, true, 1.0);
  }
  lp.set_u(3, true, 1.0);
  lp.set_c(3, -1.0);
  // Bland's rule: the default pricing cycled on a near-degenerate corner
  // (28 directions within a few degrees of each other).
  CGAL::Quadratic_program_options options;
  options.set_pricing_strategy(CGAL::QP_BLAND);
  const auto solution = CGAL::solve_linear_program(lp, CGAL::Gmpzf(), options);
  if (!solution.is_optimal() || !(CGAL::to_double(-solution.objective_value()) > 0)) return Vec3::Zero();
  Vec3 nu;
  auto value = solution.variable_values_begin();
  for (int i = 0; i < 3; ++i, ++value) nu[i] = CGAL::to_double(*value);
  return nu;
}

// The extent [lo, hi] of ν · c over the exact control points c of p: each
// within p.radius per coordinate of the stored one (|ν|₁ r); the dot
// product of three terms errs by γ3 of Σ|ν_i||c_i|, and the pad and the
// final sums round by u each of the same scale: 5u |ν|₁ max_abs in all.
std::array<double, 2> extent(const BezierPatch& p, const Vec3& nu) {
  double lo = kInf, hi = -kInf;
  for (const auto& c : p.control) {
    lo = std::min(lo, nu.dot(c));
    hi = std::max(hi, nu.dot(c));
  }
  const double pad = nu.lpNorm<1>() * (p.radius + 5 * kU * p.max_abs) * (1 + 4 * kU);
  return {lo - pad, hi + pad};
}

bool apart_along(const BezierPatch& a, const BezierPatch& b, const Vec3& nu) {
  if (!(nu.squaredNorm() > 0)) return false;
  const auto ea = extent(a, nu), eb = extent(b, nu);
  return ea[1] < eb[0] || eb[1] < ea[0];
}

} // namespace

bool apart(const BezierPatch& a, const BezierPatch& b) {
  if (!geometry::boxes_overlap(a.box(), b.box())) return true;
  // Any axis is sound (the extents are bounds); these are the ones that
  // separate two nearly coplanar triangles or two stacked ones.
  for (const BezierPatch* p : {&a, &b}) {
    const Vec3 n = corner_normal(*p);
    if (apart_along(a, b, n)) return true;
    for (int v = 0; v < 3; ++v)
      if (apart_along(a, b, n.cross(p->corner((v + 1) % 3) - p->corner(v)))) return true;
  }
  return false;
}

bool meet_only_at_corner(const BezierPatch& a, int ia, const BezierPatch& b, int ib) {
  const Vec3& x = a.corner(ia);
  const int apex_a = highorder::lattice(2, a.degree).corner(ia), apex_b = highorder::lattice(2, b.degree).corner(ib);
  // Directions from x: a's as they are, b's reversed; ν separates iff
  // ν · w > 0 for all of them.
  std::vector<Vec3> dirs;
  for (int i = 0; i < static_cast<int>(a.control.size()); ++i)
    if (i != apex_a) dirs.push_back(a.control[i] - x);
  for (int i = 0; i < static_cast<int>(b.control.size()); ++i)
    if (i != apex_b) dirs.push_back(x - b.control[i]);
  for (auto& w : dirs) {
    const double len = w.norm();
    if (!(len > 0)) return false;
    w /= len;
  }
  // The apex is exact within a's radius; each other control point within
  // its piece's radius: a margin of |ν|₁ (r_a + r) plus γ4 of the dot's scale.
  auto proves = [&](const Vec3& nu) {
    const double l1 = nu.lpNorm<1>();
    for (int i = 0; i < static_cast<int>(a.control.size()); ++i)
      if (i != apex_a && !(nu.dot(a.control[i] - x) > l1 * 2 * a.radius + 5 * kU * dot_scale(nu, a.control[i], x)))
        return false;
    for (int i = 0; i < static_cast<int>(b.control.size()); ++i)
      if (i != apex_b &&
          !(nu.dot(b.control[i] - x) < -(l1 * (a.radius + b.radius) + 5 * kU * dot_scale(nu, b.control[i], x))))
        return false;
    return true;
  };
  // Gilbert's iteration toward the point of the directions' hull nearest the
  // origin finds a separating ν quickly when the cones are far apart; thin
  // gaps (two edges a few 1e-4 rad apart, or stretched pieces whose
  // corner angles near 180 degrees) take the linear program. Both are
  // searches; only `proves` decides.
  Vec3 nu = Vec3::Zero();
  for (const auto& w : dirs) nu += w;
  nu /= static_cast<double>(dirs.size());
  for (int iteration = 0; iteration < 64; ++iteration) {
    const Vec3* worst = &dirs[0];
    for (const auto& w : dirs)
      if (nu.dot(w) < nu.dot(*worst)) worst = &w;
    if (nu.dot(*worst) > 0 && proves(nu)) return true;
    const Vec3 step = *worst - nu;
    const double ss = step.squaredNorm();
    if (!(ss > 0)) break;
    const double t = std::clamp(-nu.dot(step) / ss, 0.0, 1.0);
    if (t == 0) break;
    nu += t * step;
  }
  const Vec3 deepest = deepest_separator(dirs);
  return deepest.squaredNorm() > 0 && proves(deepest);
}

bool meet_only_along_edge(const BezierPatch& a, int a0, int a1, const BezierPatch& b, int b0, int b1) {
  const int ao = 3 - a0 - a1, bo = 3 - b0 - b1;
  const Vec3 na = corner_normal(a), nb = corner_normal(b);
  if (!(na.norm() > 0) || !(nb.norm() > 0)) return false;
  const Vec3 d = na.normalized() + nb.normalized();
  if (!(d.norm() > 0)) return false;
  const auto e = plane_basis(d.normalized());
  const Vec2 l0 = project(e, a.corner(a0)), l1 = project(e, a.corner(a1)), la = project(e, a.corner(ao)),
             lb = project(e, b.corner(bo));
  // The layout: two triangles oriented like their pieces (distortion checks
  // that), on either side of their shared edge (exact orientations), so
  // their union is a simple quadrilateral with corners l0, lb, l1, la.
  const int side = orient2d(l0, l1, la);
  if (side == 0 || orient2d(l0, l1, lb) != -side) return false;
  std::array<Vec2, 3> at_a, at_b;
  at_a[a0] = l0, at_a[a1] = l1, at_a[ao] = la;
  at_b[b0] = l0, at_b[b1] = l1, at_b[bo] = lb;
  const double L = std::max(distortion(a, at_a, e), distortion(b, at_b, e));
  if (!(L < 1)) return false;
  // A reflex corner v between boundary edges to w1 and w2 (angle φ outside)
  // lengthens paths by at most 1 / sin(φ/2). With la to the left of
  // l0 -> l1 (side > 0) the quadrilateral runs l0, lb, l1, la counter-
  // clockwise, and a corner is reflex where it turns right.
  double kappa = 1;
  for (const auto& [prev, v, next] : {std::array<Vec2, 3>{la, l0, lb}, std::array<Vec2, 3>{lb, l1, la}})
    if (orient2d(prev, v, next) * side < 0) {
      const double s = half_angle_sine_low(prev - v, next - v);
      if (!(s > 0)) return false;
      kappa = std::max(kappa, 1 / s * (1 + 4 * kU));
    }
  return L * kappa * (1 + 4 * kU) < 1;
}

bool embedded(const BezierPatch& p) {
  const Vec3 n = corner_normal(p);
  if (!(n.norm() > 0)) return false;
  const auto e = plane_basis(n.normalized());
  const std::array<Vec2, 3> at{project(e, p.corner(0)), project(e, p.corner(1)), project(e, p.corner(2))};
  return distortion(p, at, e) * (1 + 4 * kU) < 1;
}

} // namespace curvetet::check

#include "curvetet/check/bezier_patch.hpp"

#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/simplex_lattice.hpp"

#include <cmath>
#include <limits>

namespace curvetet::check {
namespace {

constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2;
using highorder::MultiIndex;

double max_abs_coordinate(const std::vector<Eigen::Vector3d>& points) {
  double m = 0;
  for (const auto& p : points) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

MultiIndex plus(MultiIndex a, int k) {
  a[k] += 1;
  return a;
}

// The blossom of the root at (σ0 × α0, σ1 × α1, σ2 × α2): α_k de Casteljau
// steps at each point σ_k. With σ_k a root corner every step copies, so the
// piece's corners that are root corners are the root's exactly.
Eigen::Vector3d blossom(const BezierPatch& root, const std::array<Barycentric, 3>& sigma, const MultiIndex& alpha,
                        std::vector<Eigen::Vector3d>& work) {
  work = root.control;
  int degree = root.degree;
  for (int k = 0; k < 3; ++k)
    for (int step = 0; step < alpha[k]; ++step, --degree) {
      const auto& from = highorder::lattice(2, degree);
      const auto& to = highorder::lattice(2, degree - 1);
      const Barycentric& l = sigma[k];
      // In place: entry i of the lower degree reads entries >= i of the
      // higher one (canonical order), so no later read sees a new value.
      for (int i = 0; i < to.size(); ++i) {
        const MultiIndex& beta = to[i];
        work[i] = l[0] * work[from.index_of(plus(beta, 0))] + l[1] * work[from.index_of(plus(beta, 1))] +
                  l[2] * work[from.index_of(plus(beta, 2))];
      }
    }
  return work[0];
}

BezierPatch restrict_patch(const BezierPatch& root, const std::array<Barycentric, 3>& corners) {
  BezierPatch p;
  p.degree = root.degree;
  p.corners = corners;
  const auto& lat = highorder::lattice(2, root.degree);
  p.control.resize(lat.size());
  std::vector<Eigen::Vector3d> work;
  for (int i = 0; i < lat.size(); ++i) p.control[i] = blossom(root, corners, lat[i], work);
  // Each step is a convex combination of three terms with exact dyadic
  // weights: at most γ3 (max |w|) of rounding, n steps, and the root's own
  // error passes through convex combinations unchanged.
  p.radius = root.radius + 4 * root.degree * kUnitRoundoff * (root.max_abs + root.radius);
  p.max_abs = max_abs_coordinate(p.control);
  return p;
}

Barycentric midpoint(const Barycentric& a, const Barycentric& b) {
  return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
}

} // namespace

const Eigen::Vector3d& BezierPatch::corner(int v) const {
  return control[highorder::lattice(2, degree).corner(v)];
}

geometry::Box3 BezierPatch::box() const {
  geometry::Box3 b{control[0], control[0]};
  for (const auto& c : control) {
    b.min = b.min.cwiseMin(c);
    b.max = b.max.cwiseMax(c);
  }
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    // One ulp outward covers the rounding of the subtraction.
    b.min[k] = std::nextafter(b.min[k] - radius, -inf);
    b.max[k] = std::nextafter(b.max[k] + radius, inf);
  }
  return b;
}

BezierPatch root_patch(int degree, std::span<const Eigen::Vector3d> nodes) {
  const auto& change = highorder::basis_change(2, degree);
  const int n = static_cast<int>(nodes.size());
  BezierPatch p;
  p.degree = degree;
  p.corners = {Barycentric{1, 0, 0}, Barycentric{0, 1, 0}, Barycentric{0, 0, 1}};
  p.control.assign(n, Eigen::Vector3d::Zero());
  double row_sum = 0;
  for (int a = 0; a < n; ++a) {
    for (int i = 0; i < n; ++i) p.control[a] += change.lagrange_to_bernstein(a, i) * nodes[i];
    row_sum = std::max(row_sum, change.abs_lagrange_to_bernstein.row(a).sum());
  }
  double node_max = 0;
  for (const auto& x : nodes) node_max = std::max(node_max, x.cwiseAbs().maxCoeff());
  // A's entries are within one ulp of the exact rationals and a dot product
  // of n terms adds n roundings: (n + 2) u |A| |f|, doubled for margin.
  // Degree 1: A is the identity and the corner rows copy exactly.
  p.radius = degree == 1 ? 0 : 2 * (n + 2) * kUnitRoundoff * row_sum * node_max;
  p.max_abs = max_abs_coordinate(p.control);
  return p;
}

std::array<BezierPatch, 4> split_patch(const BezierPatch& root, const BezierPatch& piece) {
  const auto& [c0, c1, c2] = piece.corners;
  const Barycentric m01 = midpoint(c0, c1), m12 = midpoint(c1, c2), m20 = midpoint(c2, c0);
  // The middle piece (m12, m20, m01) is the piece scaled by -1/2: in the
  // plane that keeps the orientation.
  return {restrict_patch(root, {c0, m01, m20}), restrict_patch(root, {m01, c1, m12}),
          restrict_patch(root, {m20, m12, c2}), restrict_patch(root, {m12, m20, m01})};
}

std::array<std::vector<Eigen::Vector3d>, 2> derivative_nets(const BezierPatch& p) {
  const int n = p.degree;
  const auto& from = highorder::lattice(2, n);
  const auto& to = highorder::lattice(2, n - 1);
  std::array<std::vector<Eigen::Vector3d>, 2> nets;
  for (int k = 1; k <= 2; ++k) {
    auto& net = nets[k - 1];
    net.resize(to.size());
    for (int i = 0; i < to.size(); ++i)
      net[i] = n * (p.control[from.index_of(plus(to[i], k))] - p.control[from.index_of(plus(to[i], 0))]);
  }
  return nets;
}

} // namespace curvetet::check

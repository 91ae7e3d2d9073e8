#include "curvetet/volume/chebyshev_centre.hpp"

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <limits>

namespace curvetet::volume {
namespace {

// The LP, in (x, r): maximize r subject to G (x, r) <= h, with a row
// (-n_i, 1 | -b_i) per half-space and (±e_d, 0 | ±bound) per box side. It
// is solved through its dual, min h·λ subject to Gᵀλ = (0, 0, 0, 1),
// λ >= 0: four rows, so the basis inverse is 4 × 4, and the optimal basis's
// multipliers are (x, r).
constexpr double kTolerance = 1e-12;

struct Dual {
  std::vector<Eigen::Vector4d> column; // then 4 artificial unit columns
  std::vector<double> cost;            // h; 1 for the artificials in phase 1
  int n = 0;                           // columns before the artificials
  std::array<int, 4> basis{};
  Eigen::Matrix4d inverse = Eigen::Matrix4d::Identity();
  Eigen::Vector4d value = Eigen::Vector4d(0, 0, 0, 1);
  std::vector<char> in_basis;

  Eigen::RowVector4d multipliers(const std::vector<double>& c) const {
    Eigen::RowVector4d y = Eigen::RowVector4d::Zero();
    for (int k = 0; k < 4; ++k) y += c[basis[k]] * inverse.row(k);
    return y;
  }
  void pivot(int leave, int enter, const Eigen::Vector4d& u, double step) {
    value -= step * u;
    value[leave] = step;
    inverse.row(leave) /= u[leave];
    for (int k = 0; k < 4; ++k)
      if (k != leave) inverse.row(k) -= u[k] * inverse.row(leave);
    in_basis[basis[leave]] = 0;
    basis[leave] = enter;
    in_basis[enter] = 1;
  }
  // Dantzig's rule with a cap on iterations (cycling on degenerate input
  // ends there, and the caller falls back to the exact LP).
  bool minimize(const std::vector<double>& c) {
    for (int iteration = 0; iteration < 50 + 10 * n; ++iteration) {
      const Eigen::RowVector4d y = multipliers(c);
      int enter = -1;
      double most = -kTolerance;
      for (int j = 0; j < n; ++j)
        if (!in_basis[j])
          if (const double reduced = c[j] - y.dot(column[j]); reduced < most) {
            most = reduced;
            enter = j;
          }
      if (enter < 0) return true;
      const Eigen::Vector4d u = inverse * column[enter];
      int leave = -1;
      double step = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 4; ++k)
        if (u[k] > kTolerance && value[k] / u[k] < step) {
          step = value[k] / u[k];
          leave = k;
        }
      if (leave < 0) return false; // unbounded dual: cannot happen with the box
      pivot(leave, enter, u, step);
    }
    return false;
  }
};

} // namespace

std::optional<Centre> chebyshev_centre(const std::vector<HalfSpace>& halves, const mesh::Vec3& box_lo,
                                       const mesh::Vec3& box_hi) {
  // Centred on the box and scaled by its half-diagonal, for conditioning.
  const mesh::Vec3 centre = 0.5 * (box_lo + box_hi);
  const double scale = 0.5 * (box_hi - box_lo).norm();
  if (!(scale > 0) || !std::isfinite(scale)) return std::nullopt;
  Dual d;
  for (const auto& h : halves) {
    d.column.emplace_back(-h.normal[0], -h.normal[1], -h.normal[2], 1.0);
    d.cost.push_back(-(h.offset - h.normal.dot(centre)) / scale);
  }
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {1, -1}) {
      Eigen::Vector4d g = Eigen::Vector4d::Zero();
      g[axis] = side;
      d.column.push_back(g);
      d.cost.push_back(side * ((side > 0 ? box_hi[axis] : box_lo[axis]) - centre[axis]) / scale);
    }
  d.n = static_cast<int>(d.column.size());
  for (int k = 0; k < 4; ++k) {
    d.column.push_back(Eigen::Vector4d::Unit(k));
    d.basis[k] = d.n + k;
  }
  d.in_basis.assign(d.column.size(), 0);
  for (int k = 0; k < 4; ++k) d.in_basis[d.n + k] = 1;

  // Phase 1: a feasible basis (the artificials at zero), then without them.
  std::vector<double> phase1(d.column.size(), 0.0);
  for (int k = 0; k < 4; ++k) phase1[d.n + k] = 1.0;
  if (!d.minimize(phase1)) return std::nullopt;
  for (int k = 0; k < 4; ++k)
    if (d.basis[k] >= d.n) {
      if (std::abs(d.value[k]) > 1e-9) return std::nullopt;
      int enter = -1;
      Eigen::Vector4d u;
      for (int j = 0; j < d.n && enter < 0; ++j)
        if (!d.in_basis[j] && std::abs((u = d.inverse * d.column[j])[k]) > 1e-9) enter = j;
      if (enter < 0) return std::nullopt;
      d.pivot(k, enter, u, 0.0);
    }
  std::vector<double> phase2 = d.cost;
  phase2.resize(d.column.size(), 0.0);
  if (!d.minimize(phase2)) return std::nullopt;
  const Eigen::RowVector4d y = d.multipliers(phase2);
  if (!y.allFinite()) return std::nullopt;
  return Centre{centre + scale * mesh::Vec3(y[0], y[1], y[2]), scale * y[3]};
}

} // namespace curvetet::volume

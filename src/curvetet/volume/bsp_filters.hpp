#pragma once
// INTERNAL to src/curvetet/volume/*.cpp. The double filters in front of the
// BSP's exact predicates (bsp_insert.cpp), with error bounds derived below
// rather than picked: a filter returns +1 / -1 only when the sign of the
// exact expression is certain, else 0 (the caller then decides exactly).
//
// Inputs, with u = 2^-53 the unit roundoff: points are the approximations of
// exact rational points (homogeneous.hpp `approximate`: each coordinate
// within 5u of the exact one, relative: two truncated mantissas and a
// rounded quotient); plane anchors and surface vertices are exact doubles;
// plane normals are exact rationals rounded toward zero (within 2u). Every
// floating-point operation errs by at most u relative plus, below the normal
// range, an absolute denorm_min / 2: the absolute terms below cover that.
#include <Eigen/Core>

namespace curvetet::volume::exact {

// Sign of n · (x - a), n rounded to nd (|nd|_1 = nd_l1), x approximated by
// xd, a exact. Bound: with M = max(|xd|_∞, |a|_∞), the difference errs by
// ≤ 7uM per coordinate, nd by 2u|nd| against |xd - a| ≤ 2M, and the
// three-term dot adds γ3 · 2M nd_l1: in all ≤ 17.1u nd_l1 M (factor 20).
constexpr double kSideFactor = 20;
int side_filter(const Eigen::Vector3d& nd, double nd_l1, const Eigen::Vector3d& a, const Eigen::Vector3d& xd,
                double factor = kSideFactor);

// Sign of ((q - p) × (x - p)) · n for approximated p, q, x. Bound: with M the
// largest coordinate, A = |q - p|_∞, B = |x - p|_∞, the differences err by
// ≤ 10uM + uA (resp. B), so each cross component by ≤ 20uM(A + B) + 4uAB
// plus its own γ2 · 2AB; the dot with nd adds γ3 and nd's 2u on |c| ≤ 2AB:
// in all ≤ nd_l1 (20.1uM(A + B) + 18.1uAB) (factor 24).
constexpr double kOrientFactor = 24;
int orient_in_plane_filter(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& x,
                           const Eigen::Vector3d& nd, double nd_l1, double factor = kOrientFactor);

// Whether (q - p) × (x - p) ≠ 0 is certain (1) or undecided (0): the cross
// product's components err by ≤ 20.1uM(A + B) + 8.1uAB as above (factor 24).
int not_collinear_filter(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& x,
                         double factor = kOrientFactor);

// Half-width by which a box of approximated points must grow to hold the
// exact points: 5u relative per coordinate (6u with the bound's own
// rounding), plus the absolute underflow term.
double approximation_pad(double max_abs_coordinate);

} // namespace curvetet::volume::exact

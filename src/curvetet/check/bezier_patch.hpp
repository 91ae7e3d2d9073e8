#pragma once
// A curved boundary triangle as a Bézier patch whose control points are
// known to within a derived radius, and its restriction to the dyadic
// sub-triangles of the regular midpoint split: the pieces the curved
// boundary certificate (check/curved_boundary_certificate.hpp) subdivides.
//
// Every patch is restricted from its root (the whole boundary triangle), not
// from its parent, so the radius does not grow with the depth: the root's
// control points err by the Lagrange -> Bernstein rounding, and a
// restriction adds the rounding of one blossom evaluation (convex
// combinations with dyadic weights). By the convex hull property the exact
// sub-patch lies in the hull of its exact control points, each within
// `radius` (per coordinate) of the stored one.
#include "curvetet/geometry/box_pairs.hpp"

#include <Eigen/Core>

#include <array>
#include <span>
#include <vector>

namespace curvetet::check {

// Barycentric coordinates on the root triangle; dyadic, so exact in double.
using Barycentric = std::array<double, 3>;

struct BezierPatch {
  int degree = 1;
  std::vector<Eigen::Vector3d> control; // canonical order (highorder/simplex_lattice.hpp)
  double radius = 0;                    // per-coordinate bound on |stored - exact| control point
  double max_abs = 0;                   // max |coordinate| of the stored control points
  std::array<Barycentric, 3> corners{}; // this piece's corners on its root; same orientation as the root

  const Eigen::Vector3d& corner(int v) const;
  // A closed box that contains the exact patch.
  geometry::Box3 box() const;
};

// The root patch of a boundary triangle of order `degree` (nodes in the
// internal triangle order, highorder/node_ordering.hpp).
BezierPatch root_patch(int degree, std::span<const Eigen::Vector3d> nodes);

// The four pieces of the regular midpoint split of `piece` (a restriction of
// `root`, or root itself): the three corner pieces, then the middle one, all
// oriented like the root.
std::array<BezierPatch, 4> split_patch(const BezierPatch& root, const BezierPatch& piece);

// Control-point differences n (b_{β+e_k} - b_{β+e_0}), k = 1, 2: the Bézier
// nets (degree n - 1) of the derivatives along the piece's own edges
// corner 0 -> 1 and corner 0 -> 2.
std::array<std::vector<Eigen::Vector3d>, 2> derivative_nets(const BezierPatch& p);

} // namespace curvetet::check

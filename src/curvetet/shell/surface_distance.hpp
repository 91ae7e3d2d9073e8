#pragma once
// The boundary -> input half of "ε both ways" (DESIGN.md invariant 4): a
// derived upper bound on the distance from every point of a middle patch to
// the input surface M, so that the coarsening never accepts a patch that
// leaves the ε band between its samples.
//
// Patch q of degree k, Bernstein control points b_α (|α| = k), sampled on
// the lattice of order n. By the convex hull property, control-net
// differences bound its derivatives: G for the first derivatives along the
// three edge directions, H for the second ones. Over each lattice cell,
// with d_i the distance from corner q(s_i) to the input M:
//  - first order: every point is within 2G/(3n) of some corner, and
//    dist(·, M) is 1-Lipschitz: ≤ max d_i + 2G/(3n);
//  - second order: q is within H/(2n²) of its linear interpolant on the
//    cell, which stays within max_i dist(q(s_i), t) of any single input face
//    t (the distance to a triangle is convex): ≤ min_t max_i dist(q(s_i), t)
//    + H/(2n²), t among the corners' nearest faces.
// The bound is the largest cell's smaller figure plus ρ, the rounding of the
// double evaluation (surface_distance.cpp derives it). Distances are to
// actual points of the input faces tracked by the patch's prism, so the
// bound is at least the true maximum: no tolerance.
#include "curvetet/shell/shell.hpp"

#include <memory>
#include <span>
#include <vector>

namespace curvetet::shell {

struct PatchDistance {
  double sampled = 0;   // max over lattice points of the distance to M
  double between = 0;   // added by the bound between samples
  double rounding = 0;  // ρ
  int lattice = 0;      // n
  double bound() const { return sampled + between + rounding; }
};

// Bound on max over the patch (Lagrange nodes of degree `degree` in internal
// order; degree 1 = the flat triangle of its three corners) of the distance
// to the input faces `faces` of `input`. The lattice order starts where the
// first-order term is epsilon/4 and the interpolation term epsilon/8 (at
// least 2 degree, at most 48 segments per edge) and is
// doubled once when the first bound misses epsilon only between samples.
// Returns as soon as the bound is known to exceed `epsilon`, with
// bound() > epsilon (then `sampled` may be a lower estimate).
PatchDistance patch_distance_bound(int degree, std::span<const Vec3> nodes, const mesh::SurfaceMesh& input,
                                   std::span<const int> faces, double epsilon);

// patch_distance_bound in two steps, for callers that reject a candidate as
// soon as any of its patches misses epsilon: fails_early() samples a few
// points of the first lattice (centroid, edge midpoints, inner points) and
// is true when one lies farther than epsilon - ρ (or no face is given).
// Then bound() exceeds epsilon too: it samples the same points bit for bit
// and fails at the first such. Most failing patches fail there, and
// checking every patch's probes first spares the passing patches' lattices.
class PatchDistanceCheck {
 public:
  PatchDistanceCheck(int degree, std::span<const Vec3> nodes, const mesh::SurfaceMesh& input,
                     std::span<const int> faces, double epsilon);
  ~PatchDistanceCheck();
  PatchDistanceCheck(PatchDistanceCheck&&) noexcept;
  bool fails_early() const;
  PatchDistance bound() const;

 private:
  struct Data;
  std::unique_ptr<Data> d_;
};

// The largest bound over the whole middle surface of s (each prism's patch
// against the input faces it tracks), computed in parallel; infinity when a
// prism tracks no face. `epsilon` only sets the lattices, as above.
double middle_distance_bound(const Shell& s, double epsilon);

// A point of the closed triangle (a, b, c) nearest to p, as a convex
// combination of the corners computed in double (so within a few ulps of the
// triangle even when it is degenerate).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

} // namespace curvetet::shell

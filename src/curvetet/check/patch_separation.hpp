#pragma once
// Sufficient tests that curved pieces (check/bezier_patch.hpp) are embedded
// or meet only where they must. Each returns true only with a proof: the
// exact pieces (control points within their radius) satisfy it, with every
// rounding of the double evaluation bounded (the derivations are at each
// test in patch_separation.cpp). False means "not shown at this size": the
// caller splits and tries again.
#include "curvetet/check/bezier_patch.hpp"

namespace curvetet::check {

// Pieces a and b that share no point of their roots are disjoint: their
// boxes are, or an axis (their normals, and in-plane normals of their
// edges) keeps their control hulls' extents apart. Thin pieces side by side
// in a tilted plane keep overlapping boxes at every depth; the in-plane
// axes separate them.
bool apart(const BezierPatch& a, const BezierPatch& b);

// Pieces a and b whose corners ia and ib are the same exact point x meet at
// x only: a plane through x has every other control point of a strictly on
// one side and every other one of b strictly on the other, so the hulls
// share x alone.
bool meet_only_at_corner(const BezierPatch& a, int ia, const BezierPatch& b, int ib);

// Pieces a and b whose edges a0 -> a1 and b0 -> b1 are the same exact curve
// (a0 and b0 the same point): their union is embedded, so they meet only
// along that edge. Projected along a direction d, the union is laid out on
// the quadrilateral of its projected corners; on each piece the projection
// composed with the inverse layout map is the identity plus a map whose
// derivative is at most L (Bézier nets of the derivatives), and a path in
// the quadrilateral is at most κ times the straight distance (κ > 1 only at a
// reflex corner). L κ < 1 makes the composed map injective.
bool meet_only_along_edge(const BezierPatch& a, int a0, int a1, const BezierPatch& b, int b0, int b1);

// A piece alone is embedded: the same test on its own triangle (convex, κ = 1).
bool embedded(const BezierPatch& p);

} // namespace curvetet::check

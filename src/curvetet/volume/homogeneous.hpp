#pragma once
// INTERNAL to src/curvetet/volume/*.cpp (brings GMP in). Rational points in
// homogeneous integer form, for the BSP's hot exact predicates.
//
// A point x / w with integer x and w > 0. Plane values and orientations are
// then sums of integer products: no gcd per operation, unlike mpq_class,
// whose normalisation after every product dominated the BSP on CAD meshes
// (nearly every exact call there decides a point lying on a plane).
#include "curvetet/volume/exact_mesh.hpp"

namespace curvetet::volume::exact {

struct HPoint {
  mpz_class x[3];
  mpz_class w = 1;
};

HPoint to_h(const QPoint& p);
QPoint to_q(const HPoint& p);
// Divides out the common factor of x and w (keeps sizes bounded by the
// three-plane bound however deep the cut that made the point).
void normalize(HPoint& p);
// Coordinates within 5u relative of the exact ones (two truncated mantissas,
// a rounded quotient; no overflow for any size).
Vec3 approximate(const HPoint& p);

// Plane n.x = d with integer n and d (any positive multiple of the rational
// plane it came from: signs are what matter).
struct HPlane {
  mpz_class n[3];
  mpz_class d;
};
// The plane through a with normal n (both exact rationals), scaled to integers.
HPlane to_hplane(const QPoint& a, const mpq_class n[3]);

// w times the plane's value at p: its sign is the side of p.
mpz_class value(const HPlane& plane, const HPoint& p);
// The point where segment pq meets the plane; p and q strictly on opposite
// sides, vp = value(plane, p), vq = value(plane, q). Not normalized.
HPoint crossing(const HPoint& p, const HPoint& q, const mpz_class& vp, const mpz_class& vq);
// sign(((q - p) x (x - p)) . n) for an integer normal n.
int orient_in_plane(const HPoint& p, const HPoint& q, const HPoint& x, const mpz_class n[3]);

} // namespace curvetet::volume::exact

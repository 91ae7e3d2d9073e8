#pragma once
// Conformal AMIPS energy of a linear tet and its gradient with respect to
// one corner, for the volume optimizer's inner loops. Doubles only: the
// energy ranks candidates; validity is always decided by exact orient3d.
#include "curvetet/mesh/surface_mesh.hpp"

namespace curvetet::volume {

using mesh::Vec3;

// tr(JᵀJ) / (3 det(J)^{2/3}) with J the tet's edge matrix relative to the
// regular tet: 1 for a regular tet, +inf for a flat or inverted one.
double tet_amips(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// The same energy; `grad` receives its gradient with respect to corner k
// (0..3; a, b, c, d). grad is left unset when the energy is +inf.
double tet_amips_gradient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int k, Vec3& grad);

// The energy cubed, f³ / (27 g²) without the cube root: the same order,
// for inner loops that only compare energies.
double tet_amips_cubed(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// The least energy of any tet with face (a, b, c), over every apex: a face
// that must stay (an input triangle) bounds the mesh's maximum from below.
// With L the sum of the face's squared edge lengths and A its area, the
// best apex lies above the centroid at height √(2L/9), which gives
// L / (3 (2√2 A h)^{2/3}); 1 for an equilateral face, +inf for a flat one.
double least_amips_on_face(const Vec3& a, const Vec3& b, const Vec3& c);

} // namespace curvetet::volume

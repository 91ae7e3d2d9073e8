#pragma once
// Conformal AMIPS energy of a linear tet and its gradient with respect to
// one corner, for the volume optimizer's inner loops. Doubles only: the
// energy ranks candidates; validity is always decided by exact orient3d.
#include "curvetet/mesh/surface_mesh.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace curvetet::volume {

using mesh::Vec3;

// tr(JᵀJ) / (3 det(J)^{2/3}) with J the tet's edge matrix relative to the
// regular tet: 1 for a regular tet, +inf for a flat or inverted one. This is
// the fill's internal energy (its thresholds are in this unit); what is
// reported (FillStats) is kReportedAmipsPerEnergy times it, the AMIPS of
// highorder/quality.hpp's convention (regular tet: 3).
constexpr double kReportedAmipsPerEnergy = 3;
double tet_amips(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d); // inline, below

// The same energy; `grad` receives its gradient with respect to corner k
// (0..3; a, b, c, d). grad is left unset when the energy is +inf.
double tet_amips_gradient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int k, Vec3& grad);

// The energy cubed, f³ / (27 g²) without the cube root: the same order,
// for inner loops that only compare energies.
double tet_amips_cubed(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d); // inline, below

// The least energy of any tet with face (a, b, c), over every apex: a face
// that must stay (an input triangle) bounds the mesh's maximum from below.
// With L the sum of the face's squared edge lengths and A its area, the
// best apex lies above the centroid at height √(2L/9), which gives
// L / (3 (2√2 A h)^{2/3}); 1 for an equilateral face, +inf for a flat one.
double least_amips_on_face(const Vec3& a, const Vec3& b, const Vec3& c);

// Inline: the optimizer's inner loops call these millions of times.
namespace detail {
// M = W⁻¹W⁻ᵀ for W the edge matrix of the unit-edge regular tet
// ((1,0,0), (1/2,√3/2,0), (1/2,√3/6,√(2/3))), so tr(JᵀJ) = tr(E M Eᵀ); and
// det(W⁻¹) = √2.
constexpr double kM00 = 1.5, kM11 = 1.5, kM22 = 1.5;
constexpr double kM01 = -0.5, kM02 = -0.5, kM12 = -0.5;
inline const double kDetWinv = std::sqrt(2.0);

// Cube root of a positive double: a bit-level first guess refined by two
// Halley steps (relative error < 1e-13); glibc's cbrt dominated profiles.
inline double positive_cbrt(double x) {
  if (!(x >= std::numeric_limits<double>::min()) || !(x <= 1e300)) return std::cbrt(x);
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  bits = bits / 3 + 0x2A9F7893782DA1CEull;
  double y;
  std::memcpy(&y, &bits, sizeof y);
  for (int i = 0; i < 2; ++i) {
    const double y3 = y * y * y;
    y *= (y3 + 2 * x) / (2 * y3 + x);
  }
  return y;
}

struct Edges {
  Vec3 e0, e1, e2;
  double f;    // tr(JᵀJ)
  double dete; // det(E)
};

inline Edges edges(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Edges r{b - a, c - a, d - a, 0, 0};
  r.f = kM00 * r.e0.squaredNorm() + kM11 * r.e1.squaredNorm() + kM22 * r.e2.squaredNorm() +
        2 * (kM01 * r.e0.dot(r.e1) + kM02 * r.e0.dot(r.e2) + kM12 * r.e1.dot(r.e2));
  r.dete = r.e0.dot(r.e1.cross(r.e2));
  return r;
}
} // namespace detail

inline double tet_amips(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const detail::Edges r = detail::edges(a, b, c, d);
  const double g = r.dete * detail::kDetWinv;
  if (!(g > 0)) return std::numeric_limits<double>::infinity();
  const double cg = detail::positive_cbrt(g);
  return r.f / (3 * cg * cg);
}

inline double tet_amips_cubed(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const detail::Edges r = detail::edges(a, b, c, d);
  const double g = r.dete * detail::kDetWinv;
  if (!(g > 0)) return std::numeric_limits<double>::infinity();
  return r.f * r.f * r.f / (27 * g * g);
}

} // namespace curvetet::volume

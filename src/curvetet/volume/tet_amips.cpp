#include "curvetet/volume/tet_amips.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace curvetet::volume {

namespace {

// M = W⁻¹W⁻ᵀ for W the edge matrix of the unit-edge regular tet
// ((1,0,0), (1/2,√3/2,0), (1/2,√3/6,√(2/3))), so tr(JᵀJ) = tr(E M Eᵀ); and
// det(W⁻¹) = √2.
constexpr double kM00 = 1.5, kM11 = 1.5, kM22 = 1.5;
constexpr double kM01 = -0.5, kM02 = -0.5, kM12 = -0.5;
const double kDetWinv = std::sqrt(2.0);

// Cube root of a positive double: a bit-level first guess refined by two
// Halley steps (relative error < 1e-13); glibc's cbrt dominated profiles.
double positive_cbrt(double x) {
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

Edges edges(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Edges r{b - a, c - a, d - a, 0, 0};
  r.f = kM00 * r.e0.squaredNorm() + kM11 * r.e1.squaredNorm() + kM22 * r.e2.squaredNorm() +
        2 * (kM01 * r.e0.dot(r.e1) + kM02 * r.e0.dot(r.e2) + kM12 * r.e1.dot(r.e2));
  r.dete = r.e0.dot(r.e1.cross(r.e2));
  return r;
}

} // namespace

double tet_amips(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Edges r = edges(a, b, c, d);
  const double g = r.dete * kDetWinv;
  if (!(g > 0)) return std::numeric_limits<double>::infinity();
  const double cg = positive_cbrt(g);
  return r.f / (3 * cg * cg);
}

double tet_amips_cubed(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Edges r = edges(a, b, c, d);
  const double g = r.dete * kDetWinv;
  if (!(g > 0)) return std::numeric_limits<double>::infinity();
  return r.f * r.f * r.f / (27 * g * g);
}

double tet_amips_gradient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int k, Vec3& grad) {
  const Edges r = edges(a, b, c, d);
  const double g = r.dete * kDetWinv;
  if (!(g > 0)) return std::numeric_limits<double>::infinity();
  const double cg = positive_cbrt(g);
  const double energy = r.f / (3 * cg * cg);
  // dE/d(edge matrix) = 2/(3 g^{2/3}) (E M - f/(3 det E) cof(E)); corner 0
  // moves every edge, corner i the edge i - 1 only.
  const double s = 2 / (3 * cg * cg), t = r.f / (3 * r.dete);
  const Vec3 c0 = kM00 * r.e0 + kM01 * r.e1 + kM02 * r.e2 - t * r.e1.cross(r.e2);
  const Vec3 c1 = kM01 * r.e0 + kM11 * r.e1 + kM12 * r.e2 - t * r.e2.cross(r.e0);
  const Vec3 c2 = kM02 * r.e0 + kM12 * r.e1 + kM22 * r.e2 - t * r.e0.cross(r.e1);
  switch (k) {
    case 0: grad = -s * (c0 + c1 + c2); break;
    case 1: grad = s * c0; break;
    case 2: grad = s * c1; break;
    default: grad = s * c2; break;
  }
  return energy;
}

double least_amips_on_face(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double l = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  const double area = 0.5 * (b - a).cross(c - a).norm();
  const double g = 2 * std::sqrt(2.0) * area * std::sqrt(2 * l / 9);
  if (!(g > 0)) return std::numeric_limits<double>::infinity();
  const double cg = positive_cbrt(g);
  return l / (3 * cg * cg);
}

} // namespace curvetet::volume

#include "curvetet/volume/tet_amips.hpp"

#include <cmath>
#include <limits>

namespace curvetet::volume {

using namespace detail; // the helpers the inline energies share (header)

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

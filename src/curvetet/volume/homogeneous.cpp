#include "curvetet/volume/homogeneous.hpp"

#include <cmath>

namespace curvetet::volume::exact {

HPoint to_h(const QPoint& p) {
  HPoint h;
  mpz_lcm(h.w.get_mpz_t(), p.c[0].get_den_mpz_t(), p.c[1].get_den_mpz_t());
  mpz_lcm(h.w.get_mpz_t(), h.w.get_mpz_t(), p.c[2].get_den_mpz_t());
  for (int i = 0; i < 3; ++i) h.x[i] = p.c[i].get_num() * (h.w / p.c[i].get_den());
  return h;
}

QPoint to_q(const HPoint& p) {
  QPoint q;
  for (int i = 0; i < 3; ++i) {
    q.c[i] = mpq_class(p.x[i], p.w);
    q.c[i].canonicalize();
  }
  return q;
}

void normalize(HPoint& p) {
  mpz_class g = p.w;
  for (int i = 0; i < 3 && g != 1; ++i) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), p.x[i].get_mpz_t());
  if (g == 1) return;
  for (auto& x : p.x) mpz_divexact(x.get_mpz_t(), x.get_mpz_t(), g.get_mpz_t());
  mpz_divexact(p.w.get_mpz_t(), p.w.get_mpz_t(), g.get_mpz_t());
}

Vec3 approximate(const HPoint& p) {
  // Mantissas truncated (relative error < u each), quotient rounded (< u).
  long ew = 0;
  const double mw = mpz_get_d_2exp(&ew, p.w.get_mpz_t());
  Vec3 out;
  for (int i = 0; i < 3; ++i) {
    long ex = 0;
    const double mx = mpz_get_d_2exp(&ex, p.x[i].get_mpz_t());
    out[i] = std::ldexp(mx / mw, static_cast<int>(ex - ew));
  }
  return out;
}

HPlane to_hplane(const QPoint& a, const mpq_class n[3]) {
  const mpq_class d = n[0] * a.c[0] + n[1] * a.c[1] + n[2] * a.c[2];
  mpz_class scale = d.get_den();
  for (int i = 0; i < 3; ++i) mpz_lcm(scale.get_mpz_t(), scale.get_mpz_t(), n[i].get_den_mpz_t());
  HPlane h;
  for (int i = 0; i < 3; ++i) h.n[i] = n[i].get_num() * (scale / n[i].get_den());
  h.d = d.get_num() * (scale / d.get_den());
  return h;
}

mpz_class value(const HPlane& plane, const HPoint& p) {
  mpz_class s = plane.n[0] * p.x[0];
  mpz_addmul(s.get_mpz_t(), plane.n[1].get_mpz_t(), p.x[1].get_mpz_t());
  mpz_addmul(s.get_mpz_t(), plane.n[2].get_mpz_t(), p.x[2].get_mpz_t());
  mpz_submul(s.get_mpz_t(), plane.d.get_mpz_t(), p.w.get_mpz_t());
  return s;
}

HPoint crossing(const HPoint& p, const HPoint& q, const mpz_class& vp, const mpz_class& vq) {
  // With f(p) = vp / wp: x = (f(q) p - f(p) q) / (f(q) - f(p)); the wp wq
  // factors cancel.
  HPoint h;
  for (int i = 0; i < 3; ++i) h.x[i] = vq * p.x[i] - vp * q.x[i];
  h.w = vq * p.w - vp * q.w;
  if (sgn(h.w) < 0) {
    for (auto& x : h.x) x = -x;
    h.w = -h.w;
  }
  return h;
}

int orient_in_plane(const HPoint& p, const HPoint& q, const HPoint& x, const mpz_class n[3]) {
  // (q - p) = u / (wp wq) and (x - p) = v / (wp wx) with positive denominators.
  mpz_class u[3], v[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = q.x[i] * p.w - p.x[i] * q.w;
    v[i] = x.x[i] * p.w - p.x[i] * x.w;
  }
  const mpz_class s = (u[1] * v[2] - u[2] * v[1]) * n[0] + (u[2] * v[0] - u[0] * v[2]) * n[1] +
                      (u[0] * v[1] - u[1] * v[0]) * n[2];
  return sgn(s);
}

} // namespace curvetet::volume::exact

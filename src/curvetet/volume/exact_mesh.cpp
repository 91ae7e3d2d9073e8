#include "curvetet/volume/exact_mesh.hpp"

#include "curvetet/geometry/predicates.hpp"
#include "curvetet/volume/homogeneous.hpp"

#include <algorithm>
#include <cmath>

namespace curvetet::volume::exact {

QPoint to_q(const Vec3& p) {
  QPoint q;
  for (int i = 0; i < 3; ++i) q.c[i] = p[i];
  return q;
}

namespace {
double nearest(const mpq_class& x) {
  double t = x.get_d(); // truncates toward zero
  const double up = std::nextafter(t, HUGE_VAL), down = std::nextafter(t, -HUGE_VAL);
  double best = t;
  mpq_class err = abs(x - mpq_class(t));
  for (double c : {up, down}) {
    mpq_class e = abs(x - mpq_class(c));
    if (e < err) { err = e; best = c; }
  }
  return best;
}
} // namespace

Vec3 nearest_double(const QPoint& p) { return {nearest(p.c[0]), nearest(p.c[1]), nearest(p.c[2])}; }

bool is_double(const QPoint& p) {
  for (int i = 0; i < 3; ++i)
    if (mpq_class(p.c[i].get_d()) != p.c[i]) return false;
  return true;
}

int orient3d(const QPoint& a, const QPoint& b, const QPoint& c, const QPoint& d) {
  // In integers: b - a = (xb wa - xa wb) / (wa wb) with positive
  // denominators, so the determinant of the numerators has the same sign
  // (no gcd per product, unlike mpq arithmetic).
  const HPoint ha = to_h(a), hb = to_h(b), hc = to_h(c), hd = to_h(d);
  mpz_class u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = hb.x[i] * ha.w - ha.x[i] * hb.w;
    v[i] = hc.x[i] * ha.w - ha.x[i] * hc.w;
    w[i] = hd.x[i] * ha.w - ha.x[i] * hd.w;
  }
  const mpz_class det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                        u[2] * (v[0] * w[1] - v[1] * w[0]);
  return sgn(det);
}

namespace {
// Sign of det[b-a, c-a, d-a] from double approximations whose coordinates
// are within 2u|x| of the exact ones (u = 2^-53); 0 when undecided. The bound
// covers the approximation and the rounding of the evaluation with a wide
// margin (the first-order error is below 100 u (M L^2 + L^3)).
int orient_filter(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double det = u.dot(v.cross(w));
  const double m = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), c.cwiseAbs().maxCoeff(),
                             d.cwiseAbs().maxCoeff()});
  const double l = std::max({u.cwiseAbs().maxCoeff(), v.cwiseAbs().maxCoeff(), w.cwiseAbs().maxCoeff()});
  const double bound = 1024 * 1.1102230246251565e-16 * (m * l * l + l * l * l);
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return 0;
}
} // namespace

int Vertices::add(const QPoint& p) {
  q.push_back(p);
  const bool e = is_double(p);
  d.push_back(Vec3(p.c[0].get_d(), p.c[1].get_d(), p.c[2].get_d()));
  exact.push_back(e);
  return size() - 1;
}

int Vertices::add(const Vec3& p) {
  q.push_back(to_q(p));
  d.push_back(p);
  exact.push_back(1);
  return size() - 1;
}

void Vertices::set(int i, const Vec3& p) {
  q[i] = to_q(p);
  d[i] = p;
  exact[i] = 1;
}

void Vertices::set(int i, const QPoint& p) {
  q[i] = p;
  d[i] = Vec3(p.c[0].get_d(), p.c[1].get_d(), p.c[2].get_d());
  exact[i] = is_double(p);
}

int Vertices::orient(int a, int b, int c, int e) const {
  if (exact[a] && exact[b] && exact[c] && exact[e]) return geometry::orient3d(d[a], d[b], d[c], d[e]);
  if (const int s = orient_filter(d[a], d[b], d[c], d[e])) return s;
  return exact::orient3d(q[a], q[b], q[c], q[e]);
}

int Vertices::orient_at(const std::array<int, 4>& t, int v, const Vec3& p) const {
  bool all = true;
  for (int k = 0; k < 4; ++k)
    if (t[k] != v && !exact[t[k]]) all = false;
  if (all) {
    const Vec3* x[4];
    for (int k = 0; k < 4; ++k) x[k] = t[k] == v ? &p : &d[t[k]];
    return geometry::orient3d(*x[0], *x[1], *x[2], *x[3]);
  }
  {
    const Vec3* y[4];
    for (int k = 0; k < 4; ++k) y[k] = t[k] == v ? &p : &d[t[k]];
    if (const int s = orient_filter(*y[0], *y[1], *y[2], *y[3])) return s;
  }
  QPoint pq = to_q(p);
  const QPoint* x[4];
  for (int k = 0; k < 4; ++k) x[k] = t[k] == v ? &pq : &q[t[k]];
  return exact::orient3d(*x[0], *x[1], *x[2], *x[3]);
}

} // namespace curvetet::volume::exact

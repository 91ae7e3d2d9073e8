#include "curvetet/volume/exact_mesh.hpp"

#include "curvetet/geometry/predicates.hpp"

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
  mpq_class u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = b.c[i] - a.c[i];
    v[i] = c.c[i] - a.c[i];
    w[i] = d.c[i] - a.c[i];
  }
  mpq_class det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                  u[2] * (v[0] * w[1] - v[1] * w[0]);
  return sgn(det);
}

int Vertices::add(const QPoint& p) {
  q.push_back(p);
  const bool e = is_double(p);
  d.push_back(nearest_double(p));
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
  d[i] = nearest_double(p);
  exact[i] = is_double(p);
}

int Vertices::orient(int a, int b, int c, int e) const {
  if (exact[a] && exact[b] && exact[c] && exact[e]) return geometry::orient3d(d[a], d[b], d[c], d[e]);
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
  QPoint pq = to_q(p);
  const QPoint* x[4];
  for (int k = 0; k < 4; ++k) x[k] = t[k] == v ? &pq : &q[t[k]];
  return exact::orient3d(*x[0], *x[1], *x[2], *x[3]);
}

} // namespace curvetet::volume::exact

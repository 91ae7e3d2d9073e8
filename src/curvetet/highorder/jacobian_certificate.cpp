#include "curvetet/highorder/jacobian_certificate.hpp"

#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/exact_basis.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/simplex_lattice.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <queue>
#include <stdexcept>

namespace curvetet::highorder {

std::string to_string(Validity v) {
  switch (v) {
    case Validity::positive: return "positive";
    case Validity::invalid: return "invalid";
    case Validity::undecided: return "undecided";
  }
  return "?";
}

namespace {

constexpr double kUnit = 0x1p-53; // unit roundoff of double
constexpr double kInflate = 1 + 1e-9;
double gamma(int k) { return k * kUnit / (1 - k * kUnit); }

// Bernstein polynomial on (simplex of dimension sd, degree n) x ([0,1], degree q).
struct Shape {
  int sd = 3, n = 0, q = 0;
  int simplex_count = 0, count = 0; // cached sizes (see make_shape)
  int simplex_size() const { return simplex_count; }
  int size() const { return count; }
};

Shape make_shape(int sd, int n, int q) {
  const int s = lattice_size(sd, n);
  return Shape{sd, n, q, s, s * (q + 1)};
}

double binomial(int q, int j) {
  double b = 1;
  for (int i = 1; i <= j; ++i) b = b * (q - j + i) / i;
  return b;
}

// Scaled-coefficient weights n!/alpha! * C(q, j) of every flat index (exact
// integers), built once per shape.
const std::vector<double>& weights(const Shape& s) {
  constexpr int kMaxN = 24, kMaxQ = 2;
  static std::vector<double> cache[4][kMaxN + 1][kMaxQ + 1];
  static std::once_flag once[4][kMaxN + 1][kMaxQ + 1];
  std::call_once(once[s.sd][s.n][s.q], [&s] {
    const auto& lat = lattice(s.sd, s.n);
    auto& w = cache[s.sd][s.n][s.q];
    for (int i = 0; i < lat.size() * (s.q + 1); ++i)
      w.push_back(lat.multinomial(i / (s.q + 1)) * binomial(s.q, i % (s.q + 1)));
  });
  return cache[s.sd][s.n][s.q];
}
double weight(const Shape& s, int i) { return weights(s)[i]; }

// For products in scaled form: out[index(a_i + b_j)] += a_i * b_j.
struct ConvTable {
  Shape a, b, out;
  std::vector<int> out_index; // a.size() x b.size()
  int max_pairs = 0;          // most pairs landing on one output coefficient
};

ConvTable make_conv(Shape a, Shape b) {
  ConvTable t{a, b, make_shape(a.sd, a.n + b.n, a.q + b.q), {}, 0};
  const auto& la = lattice(a.sd, a.n);
  const auto& lb = lattice(b.sd, b.n);
  const auto& lo = lattice(a.sd, a.n + b.n);
  std::vector<int> count(t.out.size(), 0);
  t.out_index.resize(static_cast<std::size_t>(a.size()) * b.size());
  for (int i = 0; i < a.size(); ++i)
    for (int j = 0; j < b.size(); ++j) {
      MultiIndex m = la[i / (a.q + 1)];
      const MultiIndex& mb = lb[j / (b.q + 1)];
      for (int k = 0; k < 4; ++k) m[k] += mb[k];
      int o = lo.index_of(m) * (t.out.q + 1) + (i % (a.q + 1)) + (j % (b.q + 1));
      t.out_index[static_cast<std::size_t>(i) * b.size() + j] = o;
      t.max_pairs = std::max(t.max_pairs, ++count[o]);
    }
  return t;
}

// The two products of det J = c1 . (c2 x c3) for one element kind and order.
struct Plan {
  Shape c1, c2, c3;
  ConvTable cross; // c2 x c3
  ConvTable dot;   // c1 . (c2 x c3)
};

const Plan& tet_plan(int order) {
  static std::unique_ptr<Plan> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[order], [order] {
    Shape c = make_shape(3, order - 1, 0);
    auto cross = make_conv(c, c);
    auto dot = make_conv(c, cross.out);
    cache[order] = std::make_unique<Plan>(Plan{c, c, c, std::move(cross), std::move(dot)});
  });
  return *cache[order];
}

const Plan& slab_plan(int k) {
  static std::unique_ptr<Plan> cache[kMaxOrder + 1];
  static std::once_flag once[kMaxOrder + 1];
  std::call_once(once[k], [k] {
    Shape uv = make_shape(2, k - 1, 1), t = make_shape(2, k, 0);
    auto cross = make_conv(uv, t);
    auto dot = make_conv(uv, cross.out);
    cache[k] = std::make_unique<Plan>(Plan{uv, uv, t, std::move(cross), std::move(dot)});
  });
  return *cache[k];
}

template <class T>
using V3 = std::array<T, 3>;

// ---- values, generic over double and mpq_class ------------------------------

template <class T>
T to_number(double x) {
  return T(x);
}

// Bernstein control points (canonical order) of nodes p (already shifted).
template <class T>
std::vector<V3<T>> control_points(int dim, int order, const std::vector<V3<T>>& p);

template <>
std::vector<V3<double>> control_points<double>(int dim, int order, const std::vector<V3<double>>& p) {
  const Eigen::MatrixXd& a = basis_change(dim, order).lagrange_to_bernstein;
  const int n = static_cast<int>(p.size());
  std::vector<V3<double>> b(n, V3<double>{0, 0, 0});
  for (int i = 0; i < n; ++i) {
    double x = 0, y = 0, z = 0;
    for (int j = 0; j < n; ++j) {
      const double w = a(i, j);
      x += w * p[j][0];
      y += w * p[j][1];
      z += w * p[j][2];
    }
    b[i] = {x, y, z};
  }
  return b;
}

template <>
std::vector<V3<mpq_class>> control_points<mpq_class>(int dim, int order, const std::vector<V3<mpq_class>>& p) {
  const auto& e = detail::exact_basis_change(dim, order);
  const int n = static_cast<int>(p.size());
  std::vector<V3<mpq_class>> b(n, V3<mpq_class>{0, 0, 0});
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const mpq_class& a = e.to_bernstein[static_cast<std::size_t>(i) * n + j];
      if (sgn(a) == 0) continue;
      for (int c = 0; c < 3; ++c) b[i][c] += a * p[j][c];
    }
  return b;
}

// Tensor coefficients x[alpha, j] of the slab map from M (degree k) and the
// cap corners (linear, elevated to degree k): j = 0 middle, j = 1 cap.
template <class T>
std::vector<V3<T>> slab_control_points(int k, const std::vector<V3<T>>& middle, const std::array<V3<T>, 3>& cap) {
  auto m = control_points<T>(2, k, middle);
  const auto& lat = lattice(2, k);
  std::vector<V3<T>> x(2 * lat.size());
  for (int i = 0; i < lat.size(); ++i) {
    x[2 * i] = m[i];
    V3<T> c{T(0), T(0), T(0)};
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 3; ++d) c[d] += T(lat[i][v]) * cap[v][d];
    for (int d = 0; d < 3; ++d) c[d] /= T(k);
    x[2 * i + 1] = c;
  }
  return x;
}

// d/dxi_k of a tensor polynomial in the simplex direction k (1..sd).
template <class T>
std::vector<V3<T>> simplex_derivative(const Shape& s, const std::vector<V3<T>>& c, int k) {
  const auto& lat = lattice(s.sd, s.n);
  const auto& low = lattice(s.sd, s.n - 1);
  std::vector<V3<T>> out(static_cast<std::size_t>(low.size()) * (s.q + 1));
  for (int i = 0; i < low.size(); ++i) {
    MultiIndex pk = low[i], p0 = low[i];
    ++pk[k];
    ++p0[0];
    const int ik = lat.index_of(pk), i0 = lat.index_of(p0);
    for (int j = 0; j <= s.q; ++j)
      for (int d = 0; d < 3; ++d)
        out[i * (s.q + 1) + j][d] = T(s.n) * (c[ik * (s.q + 1) + j][d] - c[i0 * (s.q + 1) + j][d]);
  }
  return out;
}

// d/dt of a tensor polynomial with q = 1.
template <class T>
std::vector<V3<T>> t_derivative(const std::vector<V3<T>>& c) {
  std::vector<V3<T>> out(c.size() / 2);
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int d = 0; d < 3; ++d) out[i][d] = c[2 * i + 1][d] - c[2 * i][d];
  return out;
}

template <class T>
void scale(const Shape& s, std::vector<V3<T>>& c) {
  const auto& ws = weights(s);
  for (int i = 0; i < s.size(); ++i) {
    T w(ws[i]);
    for (int d = 0; d < 3; ++d) c[i][d] *= w;
  }
}

template <class T>
std::vector<V3<T>> conv_cross(const ConvTable& t, const std::vector<V3<T>>& a, const std::vector<V3<T>>& b) {
  std::vector<V3<T>> h(t.out.size(), V3<T>{T(0), T(0), T(0)});
  const int na = t.a.size(), nb = t.b.size();
  for (int i = 0; i < na; ++i) {
    const auto& x = a[i];
    const int* row = t.out_index.data() + static_cast<std::size_t>(i) * nb;
    for (int j = 0; j < nb; ++j) {
      const auto& y = b[j];
      auto& o = h[row[j]];
      o[0] += x[1] * y[2] - x[2] * y[1];
      o[1] += x[2] * y[0] - x[0] * y[2];
      o[2] += x[0] * y[1] - x[1] * y[0];
    }
  }
  return h;
}

template <class T>
std::vector<T> conv_dot(const ConvTable& t, const std::vector<V3<T>>& a, const std::vector<V3<T>>& h) {
  std::vector<T> d(t.out.size(), T(0));
  const int na = t.a.size(), nb = t.b.size();
  for (int i = 0; i < na; ++i) {
    const auto& x = a[i];
    const int* row = t.out_index.data() + static_cast<std::size_t>(i) * nb;
    for (int j = 0; j < nb; ++j) {
      const auto& y = h[j];
      d[row[j]] += x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    }
  }
  return d;
}

// Radius of a product sum from the factors' 1-norms (na, nb) and radii (ra,
// rb): sum over pairs of ra nb + na rb + k ra rb + g na nb (see conv_*_r).
std::vector<double> conv_radius(const ConvTable& t, const std::vector<double>& na, const std::vector<double>& ra,
                                const std::vector<double>& nb, const std::vector<double>& rb, double k, double g) {
  std::vector<double> out(t.out.size(), 0.0);
  const int sa = t.a.size(), sb = t.b.size();
  for (int i = 0; i < sa; ++i) {
    const double x = na[i], rx = ra[i];
    const int* row = t.out_index.data() + static_cast<std::size_t>(i) * sb;
    for (int j = 0; j < sb; ++j) out[row[j]] += rx * (nb[j] + k * rb[j]) + x * (rb[j] + g * nb[j]);
  }
  for (double& v : out) v *= kInflate;
  return out;
}

// ---- doubles with radii -------------------------------------------------------

// Vector coefficients with one radius each: |v[i][c] - exact[i][c]| <= r[i].
struct VecR {
  std::vector<V3<double>> v;
  std::vector<double> r;
};

double norm1(const V3<double>& x) { return std::abs(x[0]) + std::abs(x[1]) + std::abs(x[2]); }
double norm_inf(const V3<double>& x) { return std::max({std::abs(x[0]), std::abs(x[1]), std::abs(x[2])}); }

// b = A p with |A| |p| bounding the rounding (A's entries are within one
// ulp of the exact ones; p carries radii rp).
VecR control_points_r(int dim, int order, const std::vector<V3<double>>& p, const std::vector<double>& rp) {
  VecR out;
  out.v = control_points<double>(dim, order, p);
  const auto& absA = basis_change(dim, order).abs_lagrange_to_bernstein;
  const int n = static_cast<int>(p.size());
  const double g = gamma(n + 4);
  std::vector<double> pn(n);
  for (int j = 0; j < n; ++j) pn[j] = norm_inf(p[j]);
  out.r.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double mag = 0, prop = 0;
    for (int j = 0; j < n; ++j) {
      mag += absA(i, j) * pn[j];
      prop += absA(i, j) * rp[j];
    }
    // the exact A differs from the rounded one by <= 2u|A|: covered by gamma(n+4)
    out.r[i] = (prop * (1 + g) + g * mag) * kInflate;
  }
  return out;
}

VecR simplex_derivative_r(const Shape& s, const VecR& c, int k) {
  VecR out;
  out.v = simplex_derivative<double>(s, c.v, k);
  const auto& lat = lattice(s.sd, s.n);
  const auto& low = lattice(s.sd, s.n - 1);
  out.r.resize(out.v.size());
  for (int i = 0; i < low.size(); ++i) {
    MultiIndex pk = low[i], p0 = low[i];
    ++pk[k];
    ++p0[0];
    const int ik = lat.index_of(pk), i0 = lat.index_of(p0);
    for (int j = 0; j <= s.q; ++j) {
      const int o = i * (s.q + 1) + j;
      out.r[o] = (s.n * (c.r[ik * (s.q + 1) + j] + c.r[i0 * (s.q + 1) + j]) + 2.01 * kUnit * norm_inf(out.v[o])) * kInflate;
    }
  }
  return out;
}

VecR t_derivative_r(const VecR& c) {
  VecR out;
  out.v = t_derivative<double>(c.v);
  out.r.resize(out.v.size());
  for (std::size_t i = 0; i < out.v.size(); ++i)
    out.r[i] = (c.r[2 * i] + c.r[2 * i + 1] + kUnit * norm_inf(out.v[i])) * kInflate;
  return out;
}

void scale_r(const Shape& s, VecR& c) {
  scale<double>(s, c.v);
  const auto& ws = weights(s);
  for (int i = 0; i < s.size(); ++i) c.r[i] = (c.r[i] * ws[i] + kUnit * norm_inf(c.v[i])) * kInflate;
}

VecR conv_cross_r(const ConvTable& t, const VecR& a, const VecR& b) {
  VecR h;
  h.v = conv_cross<double>(t, a.v, b.v);
  std::vector<double> na(a.v.size()), nb(b.v.size());
  for (std::size_t i = 0; i < na.size(); ++i) na[i] = norm1(a.v[i]);
  for (std::size_t i = 0; i < nb.size(); ++i) nb[i] = norm1(b.v[i]);
  h.r = conv_radius(t, na, a.r, nb, b.r, 2, gamma(2 * t.max_pairs + 2));
  return h;
}

struct ScalarR {
  std::vector<double> v, r;
};

ScalarR conv_dot_r(const ConvTable& t, const VecR& a, const VecR& h) {
  ScalarR d;
  d.v = conv_dot<double>(t, a.v, h.v);
  std::vector<double> na(a.v.size()), nh(h.v.size());
  for (std::size_t i = 0; i < na.size(); ++i) na[i] = norm1(a.v[i]);
  for (std::size_t i = 0; i < nh.size(); ++i) nh[i] = norm1(h.v[i]);
  d.r = conv_radius(t, na, a.r, nh, h.r, 3, gamma(3 * t.max_pairs + 2));
  return d;
}

// ---- the element kinds ---------------------------------------------------------

// Nodes minus nodes[0] (rounded; radius u |difference| per node).
template <class T>
std::vector<V3<T>> shifted(const Eigen::Vector3d* nodes, int count, const Eigen::Vector3d& origin) {
  std::vector<V3<T>> p(count);
  for (int i = 0; i < count; ++i)
    for (int d = 0; d < 3; ++d) p[i][d] = to_number<T>(nodes[i][d]) - to_number<T>(origin[d]);
  return p;
}

std::vector<double> shift_radii(const std::vector<V3<double>>& p) {
  std::vector<double> r(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) r[i] = kUnit * norm_inf(p[i]);
  return r;
}

// Scaled det J coefficients of a tet, with radii.
ScalarR tet_scaled(int order, const Eigen::Vector3d* nodes) {
  const Plan& plan = tet_plan(order);
  const int n = tet_node_count(order);
  auto p = shifted<double>(nodes, n, nodes[0]);
  VecR b = control_points_r(3, order, p, shift_radii(p));
  Shape s{3, order, 0};
  VecR g[3];
  for (int k = 0; k < 3; ++k) {
    g[k] = simplex_derivative_r(s, b, k + 1);
    scale_r(plan.c1, g[k]);
  }
  return conv_dot_r(plan.dot, g[0], conv_cross_r(plan.cross, g[1], g[2]));
}

std::vector<mpq_class> tet_scaled_exact(int order, const Eigen::Vector3d* nodes) {
  const Plan& plan = tet_plan(order);
  const int n = tet_node_count(order);
  auto p = shifted<mpq_class>(nodes, n, nodes[0]);
  auto b = control_points<mpq_class>(3, order, p);
  const Shape s = make_shape(3, order, 0);
  std::vector<V3<mpq_class>> g[3];
  for (int k = 0; k < 3; ++k) {
    g[k] = simplex_derivative<mpq_class>(s, b, k + 1);
    scale<mpq_class>(plan.c1, g[k]);
  }
  return conv_dot<mpq_class>(plan.dot, g[0], conv_cross<mpq_class>(plan.cross, g[1], g[2]));
}

ScalarR slab_scaled(int k, const Eigen::Vector3d* middle, const std::array<Eigen::Vector3d, 3>& cap, SlabSide side) {
  const Plan& plan = slab_plan(k);
  const int n = triangle_node_count(k);
  auto p = shifted<double>(middle, n, middle[0]);
  auto rp = shift_radii(p);
  std::array<V3<double>, 3> c;
  double cap_mag = 0;
  for (int v = 0; v < 3; ++v) {
    for (int d = 0; d < 3; ++d) c[v][d] = cap[v][d] - middle[0][d];
    cap_mag = std::max(cap_mag, norm_inf(c[v]));
  }
  VecR x;
  x.v = slab_control_points<double>(k, p, c);
  VecR m = control_points_r(2, k, p, rp);
  x.r.resize(x.v.size());
  for (int i = 0; i < lattice_size(2, k); ++i) {
    x.r[2 * i] = m.r[i];
    // shift (u), three products with alpha_v (exact), two sums, one division.
    x.r[2 * i + 1] = 8 * kUnit * cap_mag * kInflate;
  }
  const Shape s = make_shape(2, k, 1);
  VecR xu = simplex_derivative_r(s, x, 1), xv = simplex_derivative_r(s, x, 2), xt = t_derivative_r(x);
  scale_r(plan.c1, xu);
  scale_r(plan.c2, xv);
  scale_r(plan.c3, xt);
  ScalarR d = conv_dot_r(plan.dot, xu, conv_cross_r(plan.cross, xv, xt));
  if (side == SlabSide::bottom)
    for (double& v : d.v) v = -v;
  return d;
}

std::vector<mpq_class> slab_scaled_exact(int k, const Eigen::Vector3d* middle, const std::array<Eigen::Vector3d, 3>& cap,
                                         SlabSide side) {
  const Plan& plan = slab_plan(k);
  auto p = shifted<mpq_class>(middle, triangle_node_count(k), middle[0]);
  std::array<V3<mpq_class>, 3> c;
  for (int v = 0; v < 3; ++v)
    for (int d = 0; d < 3; ++d) c[v][d] = mpq_class(cap[v][d]) - mpq_class(middle[0][d]);
  auto x = slab_control_points<mpq_class>(k, p, c);
  const Shape s = make_shape(2, k, 1);
  auto xu = simplex_derivative<mpq_class>(s, x, 1), xv = simplex_derivative<mpq_class>(s, x, 2);
  auto xt = t_derivative<mpq_class>(x);
  scale<mpq_class>(plan.c1, xu);
  scale<mpq_class>(plan.c2, xv);
  scale<mpq_class>(plan.c3, xt);
  auto d = conv_dot<mpq_class>(plan.dot, xu, conv_cross<mpq_class>(plan.cross, xv, xt));
  if (side == SlabSide::bottom)
    for (auto& v : d) v = -v;
  return d;
}

// Scaled -> plain Bernstein coefficients (division by the exact weight).
void unscale(const Shape& s, ScalarR& d) {
  const auto& ws = weights(s);
  for (int i = 0; i < s.size(); ++i) {
    const double w = ws[i];
    d.v[i] /= w;
    d.r[i] = (d.r[i] / w + kUnit * std::abs(d.v[i])) * kInflate;
  }
}

// ---- decision and subdivision --------------------------------------------------

struct Piece {
  std::vector<double> c;
  double r = 0; // one radius for all coefficients of the piece
  std::array<Eigen::Vector3d, 4> verts;
  double t0 = 0, t1 = 1;
  int depth = 0;
  unsigned collapsed = 0; // local simplex vertices sitting on a collapsed pillar
  double lower = 0;       // min over counted coefficients of c - r
};

struct Decider {
  Shape s;
  const SimplexLattice& lat;

  // A coefficient is skipped when it belongs to a collapsed corner's fiber.
  bool skipped(const Piece& p, int flat) const {
    if (!p.collapsed) return false;
    const MultiIndex& a = lat[flat / (s.q + 1)];
    for (int v = 0; v <= s.sd; ++v)
      if ((p.collapsed >> v & 1u) && a[v] == s.n) return true;
    return false;
  }
  void bound(Piece& p) const {
    p.lower = HUGE_VAL;
    for (int i = 0; i < s.size(); ++i)
      if (!skipped(p, i)) p.lower = std::min(p.lower, p.c[i] - p.r);
  }
  // Smallest corner value proven (c + r) over the non-collapsed corners.
  double corner_upper(const Piece& p) const {
    double m = HUGE_VAL;
    for (int v = 0; v <= s.sd; ++v) {
      if (p.collapsed >> v & 1u) continue;
      const int base = lat.corner(v) * (s.q + 1);
      m = std::min({m, p.c[base] + p.r, p.c[base + s.q] + p.r});
    }
    return m;
  }

  std::pair<Piece, Piece> split(const Piece& p) const {
    // Longest simplex edge in reference coordinates vs the t interval.
    int ea = 0, eb = 1;
    double longest = -1;
    for (int a = 0; a <= s.sd; ++a)
      for (int b = a + 1; b <= s.sd; ++b) {
        double l = (p.verts[a] - p.verts[b]).norm();
        if (l > longest * (1 + 1e-12)) {
          longest = l;
          ea = a;
          eb = b;
        }
      }
    Piece x = p, y = p;
    x.depth = y.depth = p.depth + 1;
    double maxabs = 0;
    for (double v : p.c) maxabs = std::max(maxabs, std::abs(v));
    if (s.q > 0 && p.t1 - p.t0 >= longest) {
      const double tm = 0.5 * (p.t0 + p.t1);
      x.t1 = tm;
      y.t0 = tm;
      std::vector<double> w(s.q + 1);
      for (int i = 0; i < s.simplex_size(); ++i) {
        const int base = i * (s.q + 1);
        for (int j = 0; j <= s.q; ++j) w[j] = p.c[base + j];
        x.c[base] = w[0];
        y.c[base + s.q] = w[s.q];
        for (int rr = 1; rr <= s.q; ++rr) {
          for (int j = 0; j + rr <= s.q; ++j) w[j] = 0.5 * (w[j] + w[j + 1]);
          x.c[base + rr] = w[0];
          y.c[base + s.q - rr] = w[s.q - rr];
        }
      }
      x.r = y.r = (p.r + (s.q + 1) * kUnit * maxabs) * kInflate;
    } else {
      const Eigen::Vector3d mid = 0.5 * (p.verts[ea] + p.verts[eb]);
      x.verts[eb] = mid;
      y.verts[ea] = mid;
      x.collapsed &= ~(1u << eb);
      y.collapsed &= ~(1u << ea);
      std::vector<double> slice(s.simplex_size());
      for (int j = 0; j <= s.q; ++j) {
        for (int i = 0; i < s.simplex_size(); ++i) slice[i] = p.c[i * (s.q + 1) + j];
        auto [l, r] = bisect(s.sd, s.n, slice, ea, eb);
        for (int i = 0; i < s.simplex_size(); ++i) {
          x.c[i * (s.q + 1) + j] = l[i];
          y.c[i * (s.q + 1) + j] = r[i];
        }
      }
      x.r = y.r = (p.r + (s.n + 1) * kUnit * maxabs) * kInflate;
    }
    bound(x);
    bound(y);
    return {std::move(x), std::move(y)};
  }
};

Certificate region_of(const Piece& p, Certificate c, int sd) {
  c.region.assign(p.verts.begin(), p.verts.begin() + sd + 1);
  c.region_t0 = p.t0;
  c.region_t1 = p.t1;
  return c;
}

// Decides from the plain coefficients (with radii) of the whole element.
Certificate decide(const Shape& s, Piece root, const CertificateOptions& o, const std::vector<mpq_class>* exact_scaled) {
  Decider dec{s, lattice(s.sd, s.n)};
  dec.bound(root);
  Certificate cert;
  cert.min_det_upper = dec.corner_upper(root);
  if (root.lower > 0) {
    cert.validity = Validity::positive;
    cert.min_det_lower = root.lower;
    return cert;
  }
  if (cert.min_det_upper <= 0) {
    cert.validity = Validity::invalid;
    cert.min_det_lower = root.lower;
    return region_of(root, cert, s.sd);
  }
  // Blocked by rounding only? Decide the signs exactly.
  if (exact_scaled) {
    bool all_positive = true, corner_nonpositive = false;
    for (int i = 0; i < s.size(); ++i) {
      if (dec.skipped(root, i)) continue;
      if (sgn((*exact_scaled)[i]) <= 0) all_positive = false;
    }
    for (int v = 0; v <= s.sd; ++v) {
      if (root.collapsed >> v & 1u) continue;
      const int base = dec.lat.corner(v) * (s.q + 1);
      for (int j : {0, s.q})
        if (sgn((*exact_scaled)[base + j]) <= 0) corner_nonpositive = true; // corner weight is 1
    }
    cert.exact = true;
    // Exact unscaled values; mpq get_d truncates toward zero, which keeps a
    // positive lower bound and a non-positive upper bound valid.
    double lower = HUGE_VAL, upper = HUGE_VAL;
    std::vector<double> rounded(s.size());
    for (int i = 0; i < s.size(); ++i) {
      mpq_class c = (*exact_scaled)[i] / mpq_class(weight(s, i));
      rounded[i] = c.get_d();
      if (!dec.skipped(root, i)) lower = std::min(lower, rounded[i]);
    }
    for (int v = 0; v <= s.sd; ++v) {
      if (root.collapsed >> v & 1u) continue;
      const int base = dec.lat.corner(v) * (s.q + 1);
      upper = std::min({upper, rounded[base], rounded[base + s.q]});
    }
    if (all_positive) {
      cert.validity = Validity::positive;
      cert.min_det_lower = std::max(0.0, std::nextafter(lower, 0.0));
      cert.min_det_upper = std::nextafter(upper, HUGE_VAL);
      return cert;
    }
    if (corner_nonpositive) {
      cert.validity = Validity::invalid;
      cert.min_det_upper = std::min(upper, 0.0);
      cert.min_det_lower = root.lower;
      return region_of(root, cert, s.sd);
    }
    // Continue from the exact values: radius = truncation error.
    double maxabs = 0;
    for (double v : rounded) maxabs = std::max(maxabs, std::abs(v));
    root.c = rounded;
    root.r = 2 * kUnit * maxabs;
    dec.bound(root);
    cert.exact = false;
  }
  // Subdivision, most negative piece first.
  auto cmp = [](const Piece& a, const Piece& b) { return a.lower > b.lower; };
  std::priority_queue<Piece, std::vector<Piece>, decltype(cmp)> heap(cmp);
  double positive_lower = HUGE_VAL;
  heap.push(std::move(root));
  int examined = 1;
  while (!heap.empty()) {
    Piece p = heap.top();
    heap.pop();
    cert.depth = std::max(cert.depth, p.depth);
    if (p.depth >= o.max_depth || examined + 2 > o.max_pieces) {
      cert.validity = Validity::undecided;
      cert.pieces = examined;
      cert.min_det_lower = std::min(positive_lower, p.lower);
      return region_of(p, cert, s.sd);
    }
    auto [a, b] = dec.split(p);
    examined += 2;
    for (Piece* child : {&a, &b}) {
      cert.depth = std::max(cert.depth, child->depth);
      const double up = dec.corner_upper(*child);
      cert.min_det_upper = std::min(cert.min_det_upper, up);
      if (up <= 0) {
        cert.validity = Validity::invalid;
        cert.pieces = examined;
        cert.min_det_lower = std::min(positive_lower, child->lower);
        return region_of(*child, cert, s.sd);
      }
      if (child->lower > 0)
        positive_lower = std::min(positive_lower, child->lower);
      else
        heap.push(std::move(*child));
    }
  }
  cert.validity = Validity::positive;
  cert.pieces = examined;
  cert.min_det_lower = positive_lower;
  return cert;
}

Piece make_root(const Shape& s, ScalarR d) {
  Piece p;
  p.c = std::move(d.v);
  p.r = *std::max_element(d.r.begin(), d.r.end());
  if (s.sd == 3)
    p.verts = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1)};
  else
    p.verts = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d::Zero()};
  return p;
}

void check_order(int order) {
  if (order < 1 || order > kMaxOrder) throw std::invalid_argument("certificate: order must be 1..8");
}

} // namespace

Certificate certify_tet(int order, const Eigen::Vector3d* nodes, const CertificateOptions& o) {
  check_order(order);
  const Shape s = make_shape(3, 3 * (order - 1), 0);
  ScalarR d = tet_scaled(order, nodes);
  unscale(s, d);
  Piece root = make_root(s, std::move(d));
  // The exact path is only needed when the float decision is blocked by radii.
  Decider dec{s, lattice(s.sd, s.n)};
  dec.bound(root);
  const bool float_clear = root.lower > 0 || dec.corner_upper(root) <= 0;
  bool rounding_blocked = false;
  if (!float_clear && o.exact_fallback) {
    double minv = HUGE_VAL;
    for (double v : root.c) minv = std::min(minv, v);
    double cmin = HUGE_VAL;
    for (int v = 0; v < 4; ++v) cmin = std::min(cmin, std::abs(root.c[dec.lat.corner(v)]));
    rounding_blocked = minv > 0 || cmin <= root.r;
  }
  if (rounding_blocked) {
    auto exact = tet_scaled_exact(order, nodes);
    return decide(s, std::move(root), o, &exact);
  }
  return decide(s, std::move(root), o, nullptr);
}

Certificate certify_slab(int k, const Eigen::Vector3d* middle, const std::array<Eigen::Vector3d, 3>& cap,
                         SlabSide side, const std::array<bool, 3>& collapsed, const CertificateOptions& o) {
  check_order(k);
  const Shape s = make_shape(2, 3 * k - 2, 2);
  // Middle corner v is node v in the internal triangle order.
  unsigned mask = 0;
  for (int v = 0; v < 3; ++v)
    if (collapsed[v]) {
      if (cap[v] != middle[v])
        throw std::invalid_argument("certify_slab: a collapsed corner's cap point differs from the middle point");
      mask |= 1u << v;
    }
  ScalarR d = slab_scaled(k, middle, cap, side);
  unscale(s, d);
  Piece root = make_root(s, std::move(d));
  root.collapsed = mask;
  Decider dec{s, lattice(s.sd, s.n)};
  dec.bound(root);
  const bool float_clear = root.lower > 0 || dec.corner_upper(root) <= 0;
  bool rounding_blocked = false;
  if (!float_clear && o.exact_fallback) {
    double minv = HUGE_VAL;
    for (int i = 0; i < s.size(); ++i)
      if (!dec.skipped(root, i)) minv = std::min(minv, root.c[i]);
    double cmin = HUGE_VAL;
    for (int v = 0; v < 3; ++v) {
      if (mask >> v & 1u) continue;
      const int base = dec.lat.corner(v) * 3;
      cmin = std::min({cmin, std::abs(root.c[base]), std::abs(root.c[base + 2])});
    }
    rounding_blocked = minv > 0 || cmin <= root.r;
  }
  if (rounding_blocked) {
    auto exact = slab_scaled_exact(k, middle, cap, side);
    return decide(s, std::move(root), o, &exact);
  }
  return decide(s, std::move(root), o, nullptr);
}

JacobianCoefficients tet_jacobian_coefficients(int order, const Eigen::Vector3d* nodes) {
  check_order(order);
  const Shape s = make_shape(3, 3 * (order - 1), 0);
  ScalarR d = tet_scaled(order, nodes);
  unscale(s, d);
  return {3, s.n, 0, std::move(d.v), std::move(d.r)};
}

JacobianCoefficients slab_jacobian_coefficients(int k, const Eigen::Vector3d* middle,
                                                const std::array<Eigen::Vector3d, 3>& cap, SlabSide side) {
  check_order(k);
  const Shape s = make_shape(2, 3 * k - 2, 2);
  ScalarR d = slab_scaled(k, middle, cap, side);
  unscale(s, d);
  return {2, s.n, 2, std::move(d.v), std::move(d.r)};
}

std::vector<double> exact_tet_jacobian_coefficients(int order, const Eigen::Vector3d* nodes) {
  check_order(order);
  const Shape s = make_shape(3, 3 * (order - 1), 0);
  auto e = tet_scaled_exact(order, nodes);
  std::vector<double> out(e.size());
  for (int i = 0; i < s.size(); ++i) out[i] = mpq_class(e[i] / mpq_class(weight(s, i))).get_d();
  return out;
}

} // namespace curvetet::highorder

#include "curvetet/highorder/jacobian_coefficients.hpp"

#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/exact_basis.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/simplex_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace curvetet::highorder::detail {

Shape make_shape(int sd, int n, int q) {
  const int s = lattice_size(sd, n);
  return Shape{sd, n, q, s, s * (q + 1)};
}

namespace {
double binomial(int q, int j) {
  double b = 1;
  for (int i = 1; i <= j; ++i) b = b * (q - j + i) / i;
  return b;
}
} // namespace

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

namespace {


double gamma(int k) { return k * kUnit / (1 - k * kUnit); }




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
  // conv_radius sums 8 operations per pair (jacobian_coefficients.hpp, kInflate).
  if (8 * t.max_pairs + 8 > kMaxRadiusTerms) throw std::logic_error("jacobian coefficients: radius chain too long");
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
std::vector<V3<T>> slab_control_points(int k, const std::vector<V3<T>>& middle, const std::array<V3<T>, 3>& cap,
                                       MiddleBasis basis) {
  auto m = basis == MiddleBasis::bezier ? middle : control_points<T>(2, k, middle);
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

// 1-norm of every coefficient (input of the radius of a product).
template <class V>
std::vector<double> norms1(const V& values) {
  std::vector<double> n(values.size());
  for (std::size_t i = 0; i < n.size(); ++i) n[i] = norm1(values[i]);
  return n;
}

VecR conv_cross_r(const ConvTable& t, const VecR& a, const VecR& b) {
  VecR h;
  h.v = conv_cross<double>(t, a.v, b.v);
  h.r = conv_radius(t, norms1(a.v), a.r, norms1(b.v), b.r, 2, gamma(2 * t.max_pairs + 2));
  return h;
}


ScalarR conv_dot_r(const ConvTable& t, const VecR& a, const VecR& h) {
  ScalarR d;
  d.v = conv_dot<double>(t, a.v, h.v);
  d.r = conv_radius(t, norms1(a.v), a.r, norms1(h.v), h.r, 3, gamma(3 * t.max_pairs + 2));
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

} // namespace

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

ScalarR slab_scaled(int k, const Eigen::Vector3d* middle, const std::array<Eigen::Vector3d, 3>& cap, SlabSide side,
                    MiddleBasis basis) {
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
  x.v = slab_control_points<double>(k, p, c, basis);
  VecR m;
  if (basis == MiddleBasis::bezier)
    m.r = rp;
  else
    m = control_points_r(2, k, p, rp);
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
                                         SlabSide side, MiddleBasis basis) {
  const Plan& plan = slab_plan(k);
  auto p = shifted<mpq_class>(middle, triangle_node_count(k), middle[0]);
  std::array<V3<mpq_class>, 3> c;
  for (int v = 0; v < 3; ++v)
    for (int d = 0; d < 3; ++d) c[v][d] = mpq_class(cap[v][d]) - mpq_class(middle[0][d]);
  auto x = slab_control_points<mpq_class>(k, p, c, basis);
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

} // namespace curvetet::highorder::detail

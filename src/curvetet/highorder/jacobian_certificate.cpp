#include "curvetet/highorder/jacobian_certificate.hpp"

#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/jacobian_coefficients.hpp"
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

using namespace detail;

double weight(const Shape& s, int i) { return weights(s)[i]; }

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

  // The float decision is stuck only because of the radii: every counted
  // coefficient is positive but not by its radius, or a corner value is
  // within its radius of zero. Then the exact path decides.
  bool blocked_by_rounding(Piece& p) const {
    bound(p);
    if (p.lower > 0 || corner_upper(p) <= 0) return false;
    double minv = HUGE_VAL, cmin = HUGE_VAL;
    for (int i = 0; i < s.size(); ++i)
      if (!skipped(p, i)) minv = std::min(minv, p.c[i]);
    for (int v = 0; v <= s.sd; ++v) {
      if (p.collapsed >> v & 1u) continue;
      const int base = lat.corner(v) * (s.q + 1);
      cmin = std::min({cmin, std::abs(p.c[base]), std::abs(p.c[base + s.q])});
    }
    return minv > 0 || cmin <= p.r;
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

// The exact coefficients are computed (lazily) only when rounding blocks the
// float decision.
template <class ExactScaled>
Certificate certify(const Shape& s, Piece root, const CertificateOptions& o, ExactScaled exact_scaled) {
  Decider dec{s, lattice(s.sd, s.n)};
  if (o.exact_fallback && dec.blocked_by_rounding(root)) {
    const std::vector<mpq_class> exact = exact_scaled();
    return decide(s, std::move(root), o, &exact);
  }
  return decide(s, std::move(root), o, nullptr);
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
  return certify(s, std::move(root), o, [&] { return tet_scaled_exact(order, nodes); });
}

Certificate certify_slab(int k, const Eigen::Vector3d* middle, const std::array<Eigen::Vector3d, 3>& cap,
                         SlabSide side, const std::array<bool, 3>& collapsed, const CertificateOptions& o,
                         MiddleBasis basis) {
  check_order(k);
  const Shape s = make_shape(2, 3 * k - 2, 2);
  // Middle corner v: node v in the internal triangle order, or the canonical
  // corner coefficient (the Bezier control point at the corner).
  unsigned mask = 0;
  for (int v = 0; v < 3; ++v)
    if (collapsed[v]) {
      const int corner = basis == MiddleBasis::bezier ? lattice(2, k).corner(v) : v;
      if (cap[v] != middle[corner])
        throw std::invalid_argument("certify_slab: a collapsed corner's cap point differs from the middle point");
      mask |= 1u << v;
    }
  ScalarR d = slab_scaled(k, middle, cap, side, basis);
  unscale(s, d);
  Piece root = make_root(s, std::move(d));
  root.collapsed = mask;
  return certify(s, std::move(root), o, [&] { return slab_scaled_exact(k, middle, cap, side, basis); });
}

JacobianCoefficients tet_jacobian_coefficients(int order, const Eigen::Vector3d* nodes) {
  check_order(order);
  const Shape s = make_shape(3, 3 * (order - 1), 0);
  ScalarR d = tet_scaled(order, nodes);
  unscale(s, d);
  return {3, s.n, 0, std::move(d.v), std::move(d.r)};
}

JacobianCoefficients slab_jacobian_coefficients(int k, const Eigen::Vector3d* middle,
                                                const std::array<Eigen::Vector3d, 3>& cap, SlabSide side,
                                                MiddleBasis basis) {
  check_order(k);
  const Shape s = make_shape(2, 3 * k - 2, 2);
  ScalarR d = slab_scaled(k, middle, cap, side, basis);
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

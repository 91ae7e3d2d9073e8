#include "curvetet/volume/exact_optimizer.hpp"

#include "curvetet/volume/tet_amips.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace curvetet::volume::exact {

double Optimizer::energy(const Tet& t) const {
  const auto& d = m_.v.d;
  return tet_amips(d[t[0]], d[t[1]], d[t[2]], d[t[3]]);
}

double Optimizer::tet_energy(int t) {
  if (std::isnan(energy_[t])) energy_[t] = energy(stars_.corners(t));
  return energy_[t];
}

std::array<const Vec3*, 4> Optimizer::corners_at(const Tet& t, int v, const Vec3& p) const {
  std::array<const Vec3*, 4> x;
  for (int k = 0; k < 4; ++k) x[k] = t[k] == v ? &p : &m_.v.d[t[k]];
  return x;
}

double Optimizer::energy_at(const Tet& t, int v, const Vec3& p) const {
  const auto x = corners_at(t, v, p);
  return tet_amips(*x[0], *x[1], *x[2], *x[3]);
}

double Optimizer::energy_cubed_at(const Tet& t, int v, const Vec3& p) const {
  const auto x = corners_at(t, v, p);
  return tet_amips_cubed(*x[0], *x[1], *x[2], *x[3]);
}

double Optimizer::energy_gradient_at(const Tet& t, int v, const Vec3& p, Vec3& grad) const {
  const auto x = corners_at(t, v, p);
  const int corner = static_cast<int>(std::find(t.begin(), t.end(), v) - t.begin());
  return tet_amips_gradient(*x[0], *x[1], *x[2], *x[3], corner, grad);
}

bool Optimizer::star_positive_at(int v, const Vec3& p) const {
  for (int t : stars_.star(v))
    if (m_.v.orient_at(stars_.corners(t), v, p) <= 0) return false;
  return true;
}

bool Optimizer::smooth(int v) {
  if (unchanged_since(v, smooth_failed_[v])) return false;
  if (descend(v)) return true;
  smooth_failed_[v] = clock_;
  return false;
}

bool Optimizer::smooth_max(int v) {
  if (unchanged_since(v, max_failed_[v])) return false;
  if (compass_search(v)) return true;
  max_failed_[v] = clock_;
  return false;
}

bool Optimizer::relocate(int v) {
  if (m_.frozen[v] || pinned(v) || m_.v.exact[v]) return false;
  Vec3 c = Vec3::Zero();
  int n = 0;
  for (int t : stars_.star(v))
    for (int x : stars_.corners(t))
      if (x != v) {
        c += m_.v.d[x];
        ++n;
      }
  c /= n;
  const Vec3 p0 = m_.v.d[v];
  for (double a : {1.0, 0.5, 0.25, 0.1, 0.01, 1e-3, 1e-5, 1e-8}) {
    const Vec3 p = p0 + a * (c - p0);
    if (star_positive_at(v, p)) {
      move(v, p);
      return true;
    }
  }
  return false;
}

Vec3 Optimizer::best_corner(int t, int v) const {
  const Tet& q = stars_.corners(t);
  Vec3 p = m_.v.d[v];
  double len = 0;
  for (int x : q) len += (m_.v.d[x] - p).norm();
  len /= 3;
  double best = energy_at(q, v, p);
  int iterations = 0;
  for (double step = len; step > 1e-3 * len && iterations < 500; ++iterations) {
    Vec3 g;
    energy_gradient_at(q, v, p, g);
    const std::array<Vec3, 7> dirs = {g.allFinite() && g.norm() > 0 ? Vec3(-g.normalized()) : Vec3(Vec3::UnitX()),
                                      Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(),
                                      Vec3::UnitZ(), -Vec3::UnitZ()};
    bool improved = false;
    for (const Vec3& d : dirs) {
      const double e = energy_at(q, v, p + step * d);
      if (e < best) {
        best = e;
        p += step * d;
        improved = true;
        break;
      }
    }
    if (!improved) step *= 0.5;
  }
  return p;
}

bool Optimizer::descend(int v) {
  if (m_.frozen[v] || pinned(v) || stars_.star(v).empty()) return false;
  const Vec3 p0 = m_.v.d[v];
  double e0 = 0, max0 = 0, len = 0;
  Vec3 g = Vec3::Zero(); // gradient of the sum of squares
  for (int t : stars_.star(v)) {
    Vec3 gt;
    const double e = energy_gradient_at(stars_.corners(t), v, p0, gt);
    if (!std::isfinite(e)) return false;
    e0 += e * e; // squared: the worst tets dominate
    max0 = std::max(max0, e);
    g += 2 * e * gt;
    for (int x : stars_.corners(t)) len += (m_.v.d[x] - p0).norm();
  }
  len /= 3.0 * static_cast<double>(stars_.star(v).size());
  if (!(len > 0)) return false;
  auto sum_at = [&](const Vec3& p, double* mx) {
    double s = 0, m = 0;
    for (int t : stars_.star(v)) {
      const double e = energy_at(stars_.corners(t), v, p);
      s += e * e;
      m = std::max(m, e);
    }
    if (mx) *mx = m;
    return s;
  };
  if (!g.allFinite() || g.norm() == 0) return false;
  const Vec3 dir = -g.normalized();
  for (double step = 0.25 * len; step > 1e-4 * len; step *= 0.5) {
    const Vec3 p = p0 + step * dir;
    double mx;
    const double s = sum_at(p, &mx);
    if (!(s < e0) || !(mx <= max0)) continue;
    if (!star_positive_at(v, p)) continue;
    move(v, p);
    ++stats_.smooths;
    return true;
  }
  return false;
}

bool Optimizer::compass_search(int v, double goal) {
  if (m_.frozen[v] || pinned(v) || !m_.v.exact[v] || stars_.star(v).empty()) return false;
  Vec3 p = m_.v.d[v];
  std::vector<Tet> star;
  for (int t : stars_.star(v)) star.push_back(stars_.corners(t));
  const double before = max_energy_at(star, v, p, nullptr);
  const double after = descend_max(star, v, p, [&](const Vec3& q) { return star_positive_at(v, q); }, goal);
  if (!(after < before)) return false;
  move(v, p);
  ++stats_.smooths;
  return true;
}

double Optimizer::max_energy_at(const std::vector<Tet>& tets, int v, const Vec3& q, int* worst) const {
  double m = 0;
  for (int i = 0; i < static_cast<int>(tets.size()); ++i) {
    const double e = energy_at(tets[i], v, q);
    if (e > m) {
      m = e;
      if (worst) *worst = i;
    }
  }
  return m;
}

} // namespace curvetet::volume::exact

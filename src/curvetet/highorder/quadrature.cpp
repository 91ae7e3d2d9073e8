#include "curvetet/highorder/quadrature.hpp"

#include <cmath>
#include <numbers>

namespace curvetet::highorder {

void gauss_legendre(int q, std::vector<double>& x, std::vector<double>& w) {
  x.assign(q, 0.0);
  w.assign(q, 0.0);
  for (int i = 0; i < q; ++i) {
    // Newton on P_q from the Chebyshev-like initial guess.
    double z = std::cos(std::numbers::pi * (i + 0.75) / (q + 0.5)), dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= q; ++k) {
        double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (q == 1) p1 = z, p0 = 1;
      dp = q * (z * p1 - p0) / (z * z - 1);
      double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = 0.5 * (1 - z);
    w[i] = 1.0 / ((1 - z * z) * dp * dp); // 2/((1-z^2)P'^2) halved for [0,1]
  }
}

Quadrature tet_quadrature(int q) {
  std::vector<double> x, w;
  gauss_legendre(q, x, w);
  Quadrature out;
  for (int i = 0; i < q; ++i)
    for (int j = 0; j < q; ++j)
      for (int k = 0; k < q; ++k) {
        const double a = x[i], b = x[j], c = x[k];
        out.points.emplace_back(a, b * (1 - a), c * (1 - a) * (1 - b));
        out.weights.push_back(w[i] * w[j] * w[k] * (1 - a) * (1 - a) * (1 - b));
      }
  return out;
}

Quadrature triangle_quadrature(int q) {
  std::vector<double> x, w;
  gauss_legendre(q, x, w);
  Quadrature out;
  for (int i = 0; i < q; ++i)
    for (int j = 0; j < q; ++j) {
      const double a = x[i], b = x[j];
      out.points.emplace_back(a, b * (1 - a), 0.0);
      out.weights.push_back(w[i] * w[j] * (1 - a));
    }
  return out;
}

} // namespace curvetet::highorder

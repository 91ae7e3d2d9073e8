#include "curvetet/fem/manufactured.hpp"

#include "curvetet/core/error.hpp"

#include <array>
#include <cmath>
#include <limits>

namespace curvetet::fem {

BoxScaling tet_bounding_box(const mesh::TetMesh& mesh) {
  if (mesh.num_tets() == 0) throw Error(ExitCode::io, "mesh has no tetrahedra");
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (int id : mesh.tets) {
    lo = lo.cwiseMin(mesh.nodes[id]);
    hi = hi.cwiseMax(mesh.nodes[id]);
  }
  BoxScaling box{lo, (hi - lo).maxCoeff()};
  if (!(box.scale > 0)) throw Error(ExitCode::io, "mesh has zero extent");
  return box;
}

namespace {

// One Franke term c * exp(E(x_hat)) with E = sum_k E_k(x_hat_k), each E_k
// either -a (9t - b)^2 (quadratic) or -(9t + 1)/10 (linear).
struct FrankeTerm {
  double c;
  std::array<double, 3> a; // quadratic coefficient, 0 = linear term
  std::array<double, 3> b;
};

constexpr std::array<FrankeTerm, 4> kTerms = {{
    {0.75, {0.25, 0.25, 0.25}, {2, 2, 2}},
    {0.75, {1.0 / 49, 0, 0}, {-1, 0, 0}},
    {0.5, {0.25, 0.25, 0.25}, {7, 3, 5}},
    {-0.2, {1, 1, 1}, {4, 7, 5}},
}};

// Returns the term value; adds its Laplacian (in x_hat) to `lap`.
double term_value(const FrankeTerm& term, const Eigen::Vector3d& t, double* lap) {
  double e = 0, grad2 = 0, hess = 0;
  for (int k = 0; k < 3; ++k) {
    if (term.a[k] != 0) {
      double s = 9 * t[k] - term.b[k];
      e -= term.a[k] * s * s;
      double de = -18 * term.a[k] * s;
      grad2 += de * de;
      hess += -162 * term.a[k];
    } else {
      e -= (9 * t[k] + 1) / 10;
      grad2 += 0.81;
    }
  }
  double v = term.c * std::exp(e);
  if (lap) *lap += v * (grad2 + hess);
  return v;
}

} // namespace

ManufacturedSolution franke_solution(const BoxScaling& box) {
  ManufacturedSolution s;
  s.value = [box](const Eigen::Vector3d& x) {
    Eigen::Vector3d t = (x - box.origin) / box.scale;
    double u = 0;
    for (const auto& term : kTerms) u += term_value(term, t, nullptr);
    return u;
  };
  s.laplacian = [box](const Eigen::Vector3d& x) {
    Eigen::Vector3d t = (x - box.origin) / box.scale;
    double lap = 0;
    for (const auto& term : kTerms) term_value(term, t, &lap);
    return lap / (box.scale * box.scale); // chain rule: d/dx = (1/scale) d/dx_hat
  };
  return s;
}

} // namespace curvetet::fem

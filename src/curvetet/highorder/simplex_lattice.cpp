#include "curvetet/highorder/simplex_lattice.hpp"

#include <array>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace curvetet::highorder {

namespace {

constexpr int kMaxDegree = 24;

double factorial(int n) {
  double f = 1;
  for (int i = 2; i <= n; ++i) f *= i;
  return f;
}

} // namespace

SimplexLattice::SimplexLattice(int dim, int degree) : dim_(dim), degree_(degree) {
  if (dim < 1 || dim > 3 || degree < 0 || degree > kMaxDegree)
    throw std::invalid_argument("SimplexLattice: dim must be 1..3 and degree 0..24");
  const int n = degree, side = n + 1;
  int table = 1;
  for (int k = 0; k < dim; ++k) table *= side;
  lookup_.assign(table, -1);
  auto add = [&](int a1, int a2, int a3) {
    MultiIndex a{n - a1 - a2 - a3, a1, a2, a3};
    int key = a1;
    if (dim >= 2) key = key * side + a2;
    if (dim >= 3) key = key * side + a3;
    lookup_[key] = static_cast<int>(indices_.size());
    indices_.push_back(a);
    // n!/prod(alpha!) via a product of binomials keeps the value exact.
    double m = 1;
    int remaining = n;
    for (int k = 0; k <= dim; ++k) {
      m *= factorial(remaining) / (factorial(a[k]) * factorial(remaining - a[k]));
      remaining -= a[k];
    }
    multinomials_.push_back(m);
  };
  for (int a1 = 0; a1 <= n; ++a1) {
    if (dim == 1) {
      add(a1, 0, 0);
      continue;
    }
    for (int a2 = 0; a1 + a2 <= n; ++a2) {
      if (dim == 2) {
        add(a1, a2, 0);
        continue;
      }
      for (int a3 = 0; a1 + a2 + a3 <= n; ++a3) add(a1, a2, a3);
    }
  }
}

int SimplexLattice::index_of(const MultiIndex& a) const {
  const int side = degree_ + 1;
  int key = 0, sum = 0;
  for (int k = 1; k <= dim_; ++k) {
    if (a[k] < 0 || a[k] > degree_) return -1;
    key = key * side + a[k];
    sum += a[k];
  }
  if (sum > degree_) return -1;
  return lookup_[key];
}

int SimplexLattice::corner(int v) const {
  MultiIndex a{0, 0, 0, 0};
  a[v] = degree_;
  return index_of(a);
}

const SimplexLattice& lattice(int dim, int degree) {
  if (dim < 1 || dim > 3 || degree < 0 || degree > kMaxDegree)
    throw std::invalid_argument("lattice: dim must be 1..3 and degree 0..24");
  static std::array<std::array<std::unique_ptr<SimplexLattice>, kMaxDegree + 1>, 4> cache;
  static std::array<std::array<std::once_flag, kMaxDegree + 1>, 4> once;
  std::call_once(once[dim][degree], [&] { cache[dim][degree] = std::make_unique<SimplexLattice>(dim, degree); });
  return *cache[dim][degree];
}

int lattice_size(int dim, int degree) {
  long long s = 1;
  for (int k = 1; k <= dim; ++k) s = s * (degree + k) / k;
  return static_cast<int>(s);
}

} // namespace curvetet::highorder

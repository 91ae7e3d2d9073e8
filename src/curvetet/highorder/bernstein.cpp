#include "curvetet/highorder/bernstein.hpp"

#include "curvetet/highorder/exact_basis.hpp"
#include "curvetet/highorder/node_ordering.hpp"

#include <array>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace curvetet::highorder {

namespace detail {

namespace {

// Lattice coordinates (times order) of internal node i as a barycentric multi-index.
MultiIndex node_multi_index(int dim, int order, int i) {
  if (dim == 2) {
    auto [a, b] = triangle_node(order, i);
    return {order - a - b, a, b, 0};
  }
  auto [a, b, c] = tet_node(order, i);
  return {order - a - b - c, a, b, c};
}

ExactBasisChange build_exact(int dim, int order) {
  const SimplexLattice& lat = lattice(dim, order);
  const int n = lat.size();
  ExactBasisChange e;
  e.n = n;
  e.to_lagrange.resize(n * n);
  // M[i][j] = B_j(node_i) = multinomial(j) prod (node_k / order)^{alpha_jk}.
  for (int i = 0; i < n; ++i) {
    MultiIndex x = node_multi_index(dim, order, i);
    for (int j = 0; j < n; ++j) {
      const MultiIndex& a = lat[j];
      mpz_class num = 1;
      bool zero = false;
      for (int k = 0; k <= dim; ++k) {
        if (a[k] == 0) continue;
        if (x[k] == 0) {
          zero = true;
          break;
        }
        mpz_class p;
        mpz_ui_pow_ui(p.get_mpz_t(), x[k], a[k]);
        num *= p;
      }
      if (zero) continue;
      mpz_class den;
      mpz_ui_pow_ui(den.get_mpz_t(), order, order);
      mpq_class v(num * mpz_class(static_cast<unsigned long>(lat.multinomial(j))), den);
      v.canonicalize();
      e.to_lagrange[i * n + j] = v;
    }
  }
  // Gauss-Jordan on [M | I]; M is block-triangular by node support, so most
  // multipliers are zero and skipped.
  std::vector<mpq_class> a = e.to_lagrange;
  std::vector<mpq_class> inv(n * n);
  for (int i = 0; i < n; ++i) inv[i * n + i] = 1;
  for (int col = 0; col < n; ++col) {
    int piv = col;
    while (piv < n && sgn(a[piv * n + col]) == 0) ++piv;
    if (piv == n) throw std::logic_error("Bernstein-Lagrange matrix is singular");
    if (piv != col)
      for (int k = 0; k < n; ++k) {
        std::swap(a[piv * n + k], a[col * n + k]);
        std::swap(inv[piv * n + k], inv[col * n + k]);
      }
    mpq_class p = a[col * n + col];
    for (int k = 0; k < n; ++k) {
      if (sgn(a[col * n + k]) != 0) a[col * n + k] /= p;
      if (sgn(inv[col * n + k]) != 0) inv[col * n + k] /= p;
    }
    for (int r = 0; r < n; ++r) {
      if (r == col || sgn(a[r * n + col]) == 0) continue;
      mpq_class f = a[r * n + col];
      for (int k = 0; k < n; ++k) {
        if (sgn(a[col * n + k]) != 0) a[r * n + k] -= f * a[col * n + k];
        if (sgn(inv[col * n + k]) != 0) inv[r * n + k] -= f * inv[col * n + k];
      }
    }
  }
  e.to_bernstein = std::move(inv);
  return e;
}

} // namespace

const ExactBasisChange& exact_basis_change(int dim, int order) {
  if ((dim != 2 && dim != 3) || order < 1 || order > kMaxOrder)
    throw std::invalid_argument("exact_basis_change: dim 2 or 3, order 1..8");
  static std::unique_ptr<ExactBasisChange> cache[4][kMaxOrder + 1];
  static std::once_flag once[4][kMaxOrder + 1];
  std::call_once(once[dim][order],
                 [&] { cache[dim][order] = std::make_unique<ExactBasisChange>(build_exact(dim, order)); });
  return *cache[dim][order];
}

} // namespace detail

const BasisChange& basis_change(int dim, int order) {
  if ((dim != 2 && dim != 3) || order < 1 || order > kMaxOrder)
    throw std::invalid_argument("basis_change: dim 2 or 3, order 1..8");
  static std::unique_ptr<BasisChange> cache[4][kMaxOrder + 1];
  static std::once_flag once[4][kMaxOrder + 1];
  std::call_once(once[dim][order], [&] {
    const auto& e = detail::exact_basis_change(dim, order);
    auto b = std::make_unique<BasisChange>();
    b->dim = dim;
    b->order = order;
    b->lagrange_to_bernstein.resize(e.n, e.n);
    b->bernstein_to_lagrange.resize(e.n, e.n);
    for (int i = 0; i < e.n; ++i)
      for (int j = 0; j < e.n; ++j) {
        // mpq -> double is truncation in GMP; go through mpfr-free exact
        // rounding: the double nearest to num/den.
        b->lagrange_to_bernstein(i, j) = e.to_bernstein[i * e.n + j].get_d();
        b->bernstein_to_lagrange(i, j) = e.to_lagrange[i * e.n + j].get_d();
      }
    b->abs_lagrange_to_bernstein = b->lagrange_to_bernstein.cwiseAbs();
    cache[dim][order] = std::move(b);
  });
  return *cache[dim][order];
}

std::vector<double> bernstein_basis(int dim, int degree, const double* lambda) {
  const SimplexLattice& lat = lattice(dim, degree);
  // powers[k][p] = lambda_k^p
  std::array<std::array<double, 25>, 4> powers;
  for (int k = 0; k <= dim; ++k) {
    powers[k][0] = 1;
    for (int p = 1; p <= degree; ++p) powers[k][p] = powers[k][p - 1] * lambda[k];
  }
  std::vector<double> out(lat.size());
  for (int i = 0; i < lat.size(); ++i) {
    double v = lat.multinomial(i);
    for (int k = 0; k <= dim; ++k) v *= powers[k][lat[i][k]];
    out[i] = v;
  }
  return out;
}

double bernstein_eval(int dim, int degree, const double* coeffs, const double* lambda) {
  auto b = bernstein_basis(dim, degree, lambda);
  double s = 0;
  for (std::size_t i = 0; i < b.size(); ++i) s += coeffs[i] * b[i];
  return s;
}

namespace {
std::array<double, 4> barycentric(int dim, const double* xi) {
  std::array<double, 4> l{1, 0, 0, 0};
  for (int k = 0; k < dim; ++k) {
    l[k + 1] = xi[k];
    l[0] -= xi[k];
  }
  return l;
}
} // namespace

Eigen::VectorXd lagrange_basis(int dim, int order, const double* xi) {
  auto l = barycentric(dim, xi);
  auto b = bernstein_basis(dim, order, l.data());
  const auto& bc = basis_change(dim, order);
  // f(xi) = sum_j b_j B_j = sum_j B_j sum_i A_ji f_i  =>  L_i = sum_j B_j A_ji.
  Eigen::Map<const Eigen::VectorXd> bv(b.data(), static_cast<Eigen::Index>(b.size()));
  return bc.lagrange_to_bernstein.transpose() * bv;
}

Eigen::MatrixXd lagrange_gradients(int dim, int order, const double* xi) {
  auto l = barycentric(dim, xi);
  const SimplexLattice& lat = lattice(dim, order);
  const SimplexLattice& low = lattice(dim, order - 1);
  auto b = bernstein_basis(dim, order - 1, l.data());
  const auto& bc = basis_change(dim, order);
  // dB_alpha/dxi_k = n (B^{n-1}_{alpha-e_k} - B^{n-1}_{alpha-e_0}).
  Eigen::MatrixXd dB = Eigen::MatrixXd::Zero(lat.size(), dim);
  for (int i = 0; i < lat.size(); ++i) {
    const MultiIndex& a = lat[i];
    double d0 = 0;
    if (a[0] > 0) {
      MultiIndex m = a;
      --m[0];
      d0 = b[low.index_of(m)];
    }
    for (int k = 1; k <= dim; ++k) {
      double dk = 0;
      if (a[k] > 0) {
        MultiIndex m = a;
        --m[k];
        dk = b[low.index_of(m)];
      }
      dB(i, k - 1) = order * (dk - d0);
    }
  }
  return bc.lagrange_to_bernstein.transpose() * dB;
}

std::vector<double> bernstein_derivative(int dim, int degree, const std::vector<double>& c, int k) {
  const SimplexLattice& lat = lattice(dim, degree);
  const SimplexLattice& low = lattice(dim, degree - 1);
  std::vector<double> out(low.size());
  for (int i = 0; i < low.size(); ++i) {
    MultiIndex pk = low[i], p0 = low[i];
    ++pk[k];
    ++p0[0];
    out[i] = degree * (c[lat.index_of(pk)] - c[lat.index_of(p0)]);
  }
  return out;
}

std::vector<double> degree_elevate(int dim, int degree, const std::vector<double>& c) {
  const SimplexLattice& lat = lattice(dim, degree);
  const SimplexLattice& up = lattice(dim, degree + 1);
  std::vector<double> out(up.size(), 0.0);
  for (int i = 0; i < up.size(); ++i) {
    const MultiIndex& g = up[i];
    double s = 0;
    for (int k = 0; k <= dim; ++k) {
      if (g[k] == 0) continue;
      MultiIndex m = g;
      --m[k];
      s += g[k] * c[lat.index_of(m)];
    }
    out[i] = s / (degree + 1);
  }
  return out;
}

std::pair<std::vector<double>, std::vector<double>> bisect(int dim, int degree, const std::vector<double>& c, int a,
                                                           int b) {
  const SimplexLattice& lat = lattice(dim, degree);
  std::vector<double> left(c.size()), right(c.size());
  std::vector<double> work(degree + 1);
  std::vector<int> ids(degree + 1);
  // Each fiber fixes the coordinates other than a and b; along it the
  // polynomial is a 1D Bernstein polynomial in j = alpha_b.
  for (int i = 0; i < lat.size(); ++i) {
    const MultiIndex& m = lat[i];
    if (m[b] != 0) continue; // start of a fiber: alpha_b = 0
    const int s = m[a];
    for (int j = 0; j <= s; ++j) {
      MultiIndex q = m;
      q[a] = s - j;
      q[b] = j;
      ids[j] = lat.index_of(q);
      work[j] = c[ids[j]];
    }
    // left[j] = work after j rounds at position 0; right[j] = after s-j rounds at position j.
    left[ids[0]] = work[0];
    right[ids[s]] = work[s];
    for (int r = 1; r <= s; ++r) {
      for (int j = 0; j + r <= s; ++j) work[j] = 0.5 * (work[j] + work[j + 1]);
      left[ids[r]] = work[0];
      right[ids[s - r]] = work[s - r];
    }
  }
  return {std::move(left), std::move(right)};
}

} // namespace curvetet::highorder

#include "curvetet/fem/poisson.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/highorder/quadrature.hpp"

#include <Eigen/LU>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_map>

namespace curvetet::fem {

namespace {

constexpr int kMaxOrder = 8;

// Reference-element tables at the quadrature points, shared by all tets:
// geometry basis (order P) and unknown basis (order Q) values and gradients.
struct ReferenceTables {
  highorder::Quadrature rule;
  std::vector<Eigen::VectorXd> geometry_values;    // Np
  std::vector<Eigen::MatrixXd> geometry_gradients; // Np x 3
  std::vector<Eigen::VectorXd> field_values;       // Nq
  std::vector<Eigen::MatrixXd> field_gradients;    // Nq x 3
};

// Conical product with q points per direction is exact to degree 2q - 3.
ReferenceTables make_tables(int geometry_order, int field_order, int quadrature_degree) {
  ReferenceTables tables;
  int q = std::max(2, (quadrature_degree + 4) / 2);
  tables.rule = highorder::tet_quadrature(q);
  for (const auto& xi : tables.rule.points) {
    tables.geometry_values.push_back(highorder::lagrange_basis(3, geometry_order, xi.data()));
    tables.geometry_gradients.push_back(highorder::lagrange_gradients(3, geometry_order, xi.data()));
    tables.field_values.push_back(highorder::lagrange_basis(3, field_order, xi.data()));
    tables.field_gradients.push_back(highorder::lagrange_gradients(3, field_order, xi.data()));
  }
  return tables;
}

// Order-P node coordinates of tet t as a 3 x Np matrix.
Eigen::Matrix3Xd tet_coordinates(const mesh::TetMesh& mesh, int t) {
  const int n = mesh.tet_nodes();
  Eigen::Matrix3Xd x(3, n);
  const int* ids = mesh.tet(t);
  for (int i = 0; i < n; ++i) x.col(i) = mesh.nodes[ids[i]];
  return x;
}

double checked_determinant(const Eigen::Matrix3d& jacobian, int t) {
  double det = jacobian.determinant();
  if (!(det > 0))
    throw Error(ExitCode::verification,
                "tet " + std::to_string(t) + " has det J = " + std::to_string(det) + " <= 0 at a quadrature point");
  return det;
}

void check_degree(int degree) {
  if (degree < 1 || degree > kMaxOrder)
    throw Error(ExitCode::usage, "finite element degree must be in 1..8, got " + std::to_string(degree));
}

// Tet faces used once: (tet, local corner opposite the face).
std::vector<std::pair<int, int>> boundary_faces(const mesh::TetMesh& mesh) {
  struct Face {
    std::array<int, 3> key;
    int tet, opposite;
  };
  std::vector<Face> faces;
  faces.reserve(4 * static_cast<std::size_t>(mesh.num_tets()));
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const int* c = mesh.tet(t);
    for (int k = 0; k < 4; ++k) {
      std::array<int, 3> key;
      for (int i = 0, n = 0; i < 4; ++i)
        if (i != k) key[n++] = c[i];
      std::sort(key.begin(), key.end());
      faces.push_back({key, t, k});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });
  std::vector<std::pair<int, int>> once;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i == 1) once.emplace_back(faces[i].tet, faces[i].opposite);
    i = j;
  }
  return once;
}

} // namespace

PoissonProblem manufactured_problem(const ManufacturedSolution& exact) {
  auto laplacian = exact.laplacian;
  return {[laplacian](const Eigen::Vector3d& x) { return -laplacian(x); }, exact.value};
}

int default_quadrature_degree(int geometry_order, int degree) { return 2 * degree + 2 + 3 * (geometry_order - 1); }

FiniteElementField make_field(const mesh::TetMesh& mesh, int degree) {
  check_degree(degree);
  if (mesh.num_tets() == 0) throw Error(ExitCode::io, "mesh has no tetrahedra");
  FiniteElementField field;
  field.degree = degree;
  field.dofs_per_tet = highorder::tet_node_count(degree);

  // Compact corner ids so that corner dofs are 0..V-1.
  std::unordered_map<int, int> corner_id;
  std::vector<std::array<int, 4>> corners(mesh.num_tets());
  for (int t = 0; t < mesh.num_tets(); ++t)
    for (int k = 0; k < 4; ++k) {
      auto [it, inserted] = corner_id.try_emplace(mesh.tet(t)[k], static_cast<int>(corner_id.size()));
      corners[t][k] = it->second;
    }
  auto numbering = highorder::number_tet_nodes(static_cast<int>(corner_id.size()), corners, degree);
  field.tet_dofs = std::move(numbering.tet_nodes);

  // Order-P geometry basis at each order-Q lattice point: x(ξ) = X φ(ξ).
  std::vector<Eigen::VectorXd> geometry_basis(field.dofs_per_tet);
  for (int j = 0; j < field.dofs_per_tet; ++j) {
    auto b = highorder::tet_node_barycentric(degree, j);
    const double xi[3] = {b[1], b[2], b[3]};
    geometry_basis[j] = highorder::lagrange_basis(3, mesh.order, xi);
  }
  field.dof_positions.assign(numbering.num_nodes, Eigen::Vector3d::Zero());
  std::vector<char> placed(numbering.num_nodes, 0);
  for (int t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Matrix3Xd x = tet_coordinates(mesh, t);
    for (int j = 0; j < field.dofs_per_tet; ++j) {
      int dof = field.tet_dofs[static_cast<std::size_t>(t) * field.dofs_per_tet + j];
      if (placed[dof]) continue;
      placed[dof] = 1;
      field.dof_positions[dof] = x * geometry_basis[j];
    }
  }
  field.values = Eigen::VectorXd::Zero(numbering.num_nodes);
  return field;
}

PoissonResult solve_poisson(const mesh::TetMesh& mesh, const PoissonProblem& problem, const PoissonOptions& options) {
  PoissonResult result;
  result.solution = make_field(mesh, options.degree);
  FiniteElementField& field = result.solution;
  const int nq = field.dofs_per_tet;
  result.quadrature_degree =
      options.quadrature_degree > 0 ? options.quadrature_degree : default_quadrature_degree(mesh.order, field.degree);
  ReferenceTables tables = make_tables(mesh.order, field.degree, result.quadrature_degree);

  // Dirichlet dofs: those with zero barycentric weight on the corner
  // opposite a boundary face.
  std::vector<char> fixed(field.num_dofs(), 0);
  for (auto [t, k] : boundary_faces(mesh))
    for (int j = 0; j < nq; ++j)
      if (highorder::tet_node_barycentric(field.degree, j)[k] == 0.0)
        fixed[field.tet_dofs[static_cast<std::size_t>(t) * nq + j]] = 1;
  std::vector<int> free_index(field.num_dofs(), -1);
  int num_free = 0;
  for (int d = 0; d < field.num_dofs(); ++d) {
    if (fixed[d]) {
      field.values[d] = problem.dirichlet(field.dof_positions[d]);
      ++result.num_dirichlet;
    } else {
      free_index[d] = num_free++;
    }
  }

  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(mesh.num_tets()) * nq * nq);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(num_free);
  Eigen::MatrixXd stiffness(nq, nq);
  Eigen::VectorXd load(nq);
  Eigen::MatrixXd gradients(nq, 3); // physical gradients of the order-Q basis
  for (int t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Matrix3Xd x = tet_coordinates(mesh, t);
    stiffness.setZero();
    load.setZero();
    for (std::size_t p = 0; p < tables.rule.points.size(); ++p) {
      Eigen::Matrix3d jacobian = x * tables.geometry_gradients[p];
      double w = tables.rule.weights[p] * checked_determinant(jacobian, t);
      gradients.noalias() = tables.field_gradients[p] * jacobian.inverse();
      stiffness.noalias() += w * gradients * gradients.transpose();
      load += (w * problem.source(x * tables.geometry_values[p])) * tables.field_values[p];
    }
    const int* dofs = field.tet_dofs.data() + static_cast<std::size_t>(t) * nq;
    for (int i = 0; i < nq; ++i) {
      int row = free_index[dofs[i]];
      if (row < 0) continue;
      rhs[row] += load[i];
      for (int j = 0; j < nq; ++j) {
        int col = free_index[dofs[j]];
        if (col >= 0)
          triplets.emplace_back(row, col, stiffness(i, j));
        else
          rhs[row] -= stiffness(i, j) * field.values[dofs[j]];
      }
    }
  }
  if (num_free == 0) return result;

  Eigen::SparseMatrix<double> matrix(num_free, num_free);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  bool direct = options.solver == LinearSolver::direct ||
                (options.solver == LinearSolver::automatic && num_free <= kDirectSolverMaxUnknowns);
  Eigen::VectorXd u;
  if (direct) {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(matrix);
    if (solver.info() != Eigen::Success) throw Error(ExitCode::internal, "Poisson stiffness factorisation failed");
    u = solver.solve(rhs);
    if (solver.info() != Eigen::Success) throw Error(ExitCode::internal, "Poisson solve failed");
    result.solver_used = LinearSolver::direct;
  } else {
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                             Eigen::IncompleteCholesky<double>>
        solver;
    solver.setTolerance(1e-12);
    solver.setMaxIterations(std::max(1000, num_free));
    solver.compute(matrix);
    if (solver.info() != Eigen::Success) throw Error(ExitCode::internal, "incomplete Cholesky failed");
    u = solver.solve(rhs);
    if (solver.info() != Eigen::Success)
      throw Error(ExitCode::internal, "conjugate gradients did not converge (residual " +
                                          std::to_string(solver.error()) + ")");
    result.solver_used = LinearSolver::conjugate_gradient;
    result.cg_iterations = static_cast<int>(solver.iterations());
  }
  for (int d = 0; d < field.num_dofs(); ++d)
    if (free_index[d] >= 0) field.values[d] = u[free_index[d]];
  return result;
}

L2Norms l2_error(const mesh::TetMesh& mesh, const FiniteElementField& field, const ScalarFunction& exact,
                 int quadrature_degree) {
  int degree = quadrature_degree > 0 ? quadrature_degree : default_quadrature_degree(mesh.order, field.degree) + 2;
  ReferenceTables tables = make_tables(mesh.order, field.degree, degree);
  const int nq = field.dofs_per_tet;
  double error2 = 0, exact2 = 0, volume = 0;
  Eigen::VectorXd local(nq);
  for (int t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Matrix3Xd x = tet_coordinates(mesh, t);
    const int* dofs = field.tet_dofs.data() + static_cast<std::size_t>(t) * nq;
    for (int j = 0; j < nq; ++j) local[j] = field.values[dofs[j]];
    for (std::size_t p = 0; p < tables.rule.points.size(); ++p) {
      Eigen::Matrix3d jacobian = x * tables.geometry_gradients[p];
      double w = tables.rule.weights[p] * checked_determinant(jacobian, t);
      double u = exact(x * tables.geometry_values[p]);
      double e = tables.field_values[p].dot(local) - u;
      error2 += w * e * e;
      exact2 += w * u * u;
      volume += w;
    }
  }
  return {std::sqrt(error2), std::sqrt(exact2), volume};
}

} // namespace curvetet::fem

#pragma once
// Dirichlet problem for the Poisson equation on a curved tet mesh:
//   -Δu = f in Ω,   u = g on ∂Ω,
// Ω = the union of the order-P tets of `mesh` (geometry of order P, from the
// element map highorder::tet_point), unknowns = continuous order-Q Lagrange
// elements (Q = 1..8; Q < P is "superparametric", the paper's §6.4 setup is
// P = 4, Q = 2). Isoparametric means Q = P.
//
// Unknowns: numbered conformingly from the tets' corner node ids
// (highorder::number_tet_nodes with order Q, corners first, compacted to
// 0..V-1 in order of first appearance); dof j of tet t sits at the image,
// through tet t's order-P element map, of the order-Q lattice point
// tet_node_barycentric(Q, j). Shared faces are conforming, so every dof has
// one position.
//
// Boundary: the tet faces used by exactly one tet (matched by corner ids);
// the mesh's listed boundary triangles are not used. Dirichlet dofs are the
// dofs on those faces; they take g at their position (nodal interpolation,
// as DOLFINx does) and are eliminated, so the remaining system is SPD and is
// solved with Eigen::SimplicialLDLT (direct) or, for large systems where the
// 3D fill-in of the factor dominates, with conjugate gradients
// preconditioned by incomplete Cholesky to a relative residual of 1e-12.
//
// Quadrature (conical product, highorder/quadrature.hpp, exact to degree
// 2q-3 with q points per direction): degree d = 2Q + 2 + 3(P-1). On affine
// tets (P = 1, or curved-order nodes placed affinely) the stiffness
// integrand has degree 2(Q-1) and the mass-type terms u_h^2, f φ with a
// polynomial f of degree <= 2 have degree <= 2Q + 2, so they are exact. On
// curved tets the stiffness integrand is rational (∇φ adj(J) adj(J)^T ∇φ /
// det J) and f∘x has degree deg(f)·P, so no finite rule is exact; the extra
// 3(P-1) is the degree of det J, the weight of every integrand, which keeps
// the quadrature error well below the discretisation error (measured: the
// same L2 error as DOLFINx to 5e-6 relative on a curved P = 2 ball). The
// geometry Jacobian is evaluated at every quadrature point from the order-P
// element map. `quadrature_degree` overrides d.
//
// Throws Error(verification) when det J <= 0 at a quadrature point (an
// invalid element), Error(internal) when the factorisation fails or CG does
// not converge.
#include "curvetet/fem/manufactured.hpp"
#include "curvetet/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace curvetet::fem {

using ScalarFunction = std::function<double(const Eigen::Vector3d&)>;

struct PoissonProblem {
  ScalarFunction source;    // f in -Δu = f
  ScalarFunction dirichlet; // g on ∂Ω
};

// -Δu = f with f = -laplacian and g = value: u is the exact solution.
PoissonProblem manufactured_problem(const ManufacturedSolution& exact);

enum class LinearSolver {
  automatic,         // direct up to kDirectSolverMaxUnknowns free dofs, else CG
  direct,            // SimplicialLDLT
  conjugate_gradient // CG + IncompleteCholesky, relative residual 1e-12
};
constexpr int kDirectSolverMaxUnknowns = 20000;

struct PoissonOptions {
  int degree = 2;            // Q, order of the unknowns (1..8)
  int quadrature_degree = 0; // 0 = automatic (see above)
  LinearSolver solver = LinearSolver::automatic;
};

// A continuous order-Q field on the mesh.
struct FiniteElementField {
  int degree = 2;                             // Q
  int dofs_per_tet = 0;                       // (Q+1)(Q+2)(Q+3)/6
  std::vector<int> tet_dofs;                  // num_tets x dofs_per_tet, internal (Gmsh) order
  std::vector<Eigen::Vector3d> dof_positions; // physical position of each dof
  Eigen::VectorXd values;                     // one per dof
  int num_dofs() const { return static_cast<int>(dof_positions.size()); }
};

struct PoissonResult {
  FiniteElementField solution;
  int num_dirichlet = 0;    // dofs fixed by g
  int quadrature_degree = 0;
  LinearSolver solver_used = LinearSolver::direct;
  int cg_iterations = 0; // 0 for the direct solver
};

// Automatic quadrature degree for geometry order P and unknowns of order Q.
int default_quadrature_degree(int geometry_order, int degree);

// Dof layout and positions only (values zero). Throws Error(usage) for Q
// outside 1..8.
FiniteElementField make_field(const mesh::TetMesh& mesh, int degree);

PoissonResult solve_poisson(const mesh::TetMesh& mesh, const PoissonProblem& problem, const PoissonOptions& options = {});

struct L2Norms {
  double error = 0; // ||u_h - u||_L2(Ω)
  double exact = 0; // ||u||_L2(Ω)
  double volume = 0;
};
// By quadrature of degree `quadrature_degree` (0 = the automatic degree of
// the field + 2) on the curved elements.
L2Norms l2_error(const mesh::TetMesh& mesh, const FiniteElementField& field, const ScalarFunction& exact,
                 int quadrature_degree = 0);

} // namespace curvetet::fem

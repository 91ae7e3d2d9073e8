// Poisson solve (assembly + SimplicialLDLT + L2 error) on a structured unit
// cube, n^3 cells of 6 Kuhn tets each, straight order-P geometry (the
// high-order nodes placed affinely: the cost of curved geometry is the
// quadrature and Jacobian work, which does not depend on where the nodes
// are), order-Q unknowns. Counters: dofs, tets, relative L2 error.
#include "curvetet/fem/manufactured.hpp"
#include "curvetet/fem/poisson.hpp"
#include "curvetet/highorder/conforming_nodes.hpp"

#include <Eigen/Geometry>
#include <benchmark/benchmark.h>

#include <array>

namespace {

using namespace curvetet;

// Kuhn subdivision: every tet follows a monotone path 000 -> 111 through the
// cell; all six are positively oriented.
mesh::TetMesh structured_cube(int n, int order) {
  auto vertex = [n](int i, int j, int k) { return (i * (n + 1) + j) * (n + 1) + k; };
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) corners.emplace_back(double(i) / n, double(j) / n, double(k) / n);
  const std::array<std::array<int, 3>, 6> paths = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  std::vector<std::array<int, 4>> tets;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& path : paths) {
          std::array<int, 3> p = {i, j, k};
          std::array<int, 4> tet;
          tet[0] = vertex(p[0], p[1], p[2]);
          for (int s = 0; s < 3; ++s) {
            ++p[path[s]];
            tet[s + 1] = vertex(p[0], p[1], p[2]);
          }
          Eigen::Vector3d a = corners[tet[0]];
          double det = (corners[tet[1]] - a).dot((corners[tet[2]] - a).cross(corners[tet[3]] - a));
          if (det < 0) std::swap(tet[2], tet[3]);
          tets.push_back(tet);
        }
  auto numbering = highorder::number_tet_nodes(static_cast<int>(corners.size()), tets, order);
  mesh::TetMesh m;
  m.order = order;
  m.nodes.resize(numbering.num_nodes);
  m.tets = numbering.tet_nodes;
  const int per_tet = m.tet_nodes();
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int i = 0; i < per_tet; ++i) {
      auto b = highorder::tet_node_barycentric(order, i);
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int c = 0; c < 4; ++c) x += b[c] * corners[tets[t][c]];
      m.nodes[m.tets[t * per_tet + i]] = x;
    }
  return m;
}

void BM_PoissonCube(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), order = static_cast<int>(state.range(1));
  mesh::TetMesh m = structured_cube(n, order);
  fem::ManufacturedSolution exact = fem::franke_solution();
  fem::PoissonOptions options;
  options.degree = static_cast<int>(state.range(2));
  double relative = 0;
  int dofs = 0;
  for (auto _ : state) {
    fem::PoissonResult r = fem::solve_poisson(m, fem::manufactured_problem(exact), options);
    fem::L2Norms norms = fem::l2_error(m, r.solution, exact.value);
    relative = norms.error / norms.exact;
    dofs = r.solution.num_dofs();
  }
  state.counters["tets"] = m.num_tets();
  state.counters["dofs"] = dofs;
  state.counters["rel_l2"] = relative;
}
// {cells per side, geometry order P, unknown order Q}
BENCHMARK(BM_PoissonCube)
    ->Args({8, 1, 2})
    ->Args({16, 1, 2})
    ->Args({24, 1, 2})
    ->Args({8, 2, 2})
    ->Args({8, 4, 2})
    ->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();

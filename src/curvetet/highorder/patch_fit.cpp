#include "curvetet/highorder/patch_fit.hpp"

#include "curvetet/highorder/bernstein.hpp"
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/node_ordering.hpp"

#include <Eigen/Dense>

#include <map>
#include <stdexcept>

namespace curvetet::highorder {

PatchFit fit_patch_star(const PatchFitProblem& p) {
  const int k = p.degree;
  const int per_tri = triangle_node_count(k);
  const int num_corners = static_cast<int>(p.corners.size());
  const auto numbering = number_triangle_nodes(num_corners, p.triangles, k);

  std::map<std::pair<int, int>, const PatchFitProblem::FixedEdge*> fixed_edge;
  for (const auto& e : p.fixed_edges) {
    if (static_cast<int>(e.nodes.size()) != k - 1) throw std::invalid_argument("fit_patch_star: fixed edge needs k-1 nodes");
    fixed_edge[{e.a, e.b}] = &e;
  }

  // Position of every global node: the flat (linear) one, or its fixed one.
  std::vector<Eigen::Vector3d> position(numbering.num_nodes, Eigen::Vector3d::Zero());
  std::vector<char> fixed(numbering.num_nodes, 0);
  for (int c = 0; c < num_corners; ++c) {
    position[c] = p.corners[c];
    fixed[c] = 1;
  }
  for (std::size_t t = 0; t < p.triangles.size(); ++t) {
    const auto& tri = p.triangles[t];
    for (int i = 0; i < per_tri; ++i) {
      const int g = numbering.tet_nodes[t * per_tri + i];
      if (g < num_corners) continue;
      auto n = triangle_node(k, i);
      const int w[3] = {k - n[0] - n[1], n[0], n[1]};
      position[g] = (w[0] * p.corners[tri[0]] + w[1] * p.corners[tri[1]] + w[2] * p.corners[tri[2]]) / double(k);
      // An edge node (one weight zero) of a fixed edge takes its given place.
      for (int z = 0; z < 3; ++z) {
        if (w[z] != 0) continue;
        const int ia = (z + 1) % 3, ib = (z + 2) % 3;
        const int a = tri[ia], b = tri[ib];
        if (auto it = fixed_edge.find({a, b}); it != fixed_edge.end()) {
          position[g] = it->second->nodes[w[ib] - 1];
          fixed[g] = 1;
        } else if (auto jt = fixed_edge.find({b, a}); jt != fixed_edge.end()) {
          position[g] = jt->second->nodes[w[ia] - 1];
          fixed[g] = 1;
        }
      }
    }
  }

  std::vector<int> free_index(numbering.num_nodes, -1);
  int nfree = 0;
  for (int g = 0; g < numbering.num_nodes; ++g)
    if (!fixed[g]) free_index[g] = nfree++;

  PatchFit out;
  out.free_nodes = nfree;
  if (nfree > 0 && !p.samples.empty()) {
    // Unknowns: displacement of each free node from its flat position.
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(p.samples.size()), nfree);
    Eigen::MatrixXd rhs(static_cast<Eigen::Index>(p.samples.size()), 3);
    for (std::size_t s = 0; s < p.samples.size(); ++s) {
      const auto& sample = p.samples[s];
      const double xi[2] = {sample.uv.x(), sample.uv.y()};
      Eigen::VectorXd basis = lagrange_basis(2, k, xi);
      Eigen::Vector3d current = Eigen::Vector3d::Zero();
      for (int i = 0; i < per_tri; ++i) {
        const int g = numbering.tet_nodes[sample.triangle * per_tri + i];
        current += basis[i] * position[g];
        if (free_index[g] >= 0) A(static_cast<Eigen::Index>(s), free_index[g]) += basis[i];
      }
      rhs.row(static_cast<Eigen::Index>(s)) = (sample.target - current).transpose();
    }
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
    Eigen::MatrixXd delta = cod.solve(rhs);
    for (int g = 0; g < numbering.num_nodes; ++g)
      if (free_index[g] >= 0) position[g] += delta.row(free_index[g]).transpose();
  }

  out.nodes.resize(p.triangles.size());
  for (std::size_t t = 0; t < p.triangles.size(); ++t)
    for (int i = 0; i < per_tri; ++i) out.nodes[t].push_back(position[numbering.tet_nodes[t * per_tri + i]]);
  for (const auto& sample : p.samples) {
    const double xi[2] = {sample.uv.x(), sample.uv.y()};
    Eigen::VectorXd basis = lagrange_basis(2, k, xi);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i = 0; i < per_tri; ++i) x += basis[i] * out.nodes[sample.triangle][i];
    out.max_residual = std::max(out.max_residual, (x - sample.target).norm());
  }
  return out;
}

} // namespace curvetet::highorder

#pragma once
// Straight order-P tet meshes built in code, for the volume tests.
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/mesh/tet_mesh.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace curvetet::test {

// A mesh of straight order-P tets over `points` (vertex i = node i; tets
// positive as given), nodes numbered by highorder::number_tet_nodes; tets
// tagged kDomainTag; boundary = the hull faces (faces used once), outward,
// tagged kBoundaryTag.
inline mesh::TetMesh straight_mesh(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 4>>& tets,
                                   int order) {
  using Face = std::array<int, 3>;
  const auto sorted_face = [](int a, int b, int c) {
    Face f{a, b, c};
    std::sort(f.begin(), f.end());
    return f;
  };
  const auto numbering = highorder::number_tet_nodes(static_cast<int>(points.size()), tets, order);
  mesh::TetMesh m;
  m.order = order;
  m.tets = numbering.tet_nodes;
  m.nodes.assign(numbering.num_nodes, Eigen::Vector3d::Zero());
  const int np = m.tet_nodes();
  for (int t = 0; t < static_cast<int>(tets.size()); ++t)
    for (int i = 0; i < np; ++i) {
      const auto w = highorder::tet_node_barycentric(order, i);
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (int k = 0; k < 4; ++k) p += w[k] * points[tets[t][k]];
      m.nodes[m.tets[t * np + i]] = p;
    }
  using highorder::kTetFaces;
  std::map<Face, int> uses;
  for (const auto& c : tets)
    for (const auto& f : kTetFaces) ++uses[sorted_face(c[f[0]], c[f[1]], c[f[2]])];
  for (int t = 0; t < static_cast<int>(tets.size()); ++t)
    for (int f = 0; f < 4; ++f) {
      const auto& c = tets[t];
      if (uses[sorted_face(c[kTetFaces[f][0]], c[kTetFaces[f][1]], c[kTetFaces[f][2]])] != 1) continue;
      for (int i : highorder::tet_face_nodes(order, f)) m.boundary.push_back(m.tets[t * np + i]);
      m.boundary_tags.push_back(mesh::kBoundaryTag);
    }
  m.tet_tags.assign(tets.size(), mesh::kDomainTag);
  mesh::set_default_groups(m);
  return m;
}

} // namespace curvetet::test

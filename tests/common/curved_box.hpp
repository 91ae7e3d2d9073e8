#pragma once
// A conforming curved tet mesh built in code, for io/check tests and
// benchmarks: the unit cube split into cells^3 cubes, each cube into 6
// positive Kuhn tets (all around the main diagonal), high-order nodes on the
// straight lattice, then every node moved by a smooth bend
//   phi(x) = x + bend * (sin(pi y) sin(pi z), sin(pi z) sin(pi x), sin(pi x) sin(pi y)) / pi
// so shared edges and faces stay shared (nodes are keyed by their exact
// integer lattice position). Boundary triangles are the tet faces seen once,
// outward, with the faces' high-order nodes.
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/mesh/tet_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>

namespace curvetet::testing {

inline mesh::TetMesh curved_box(int order, int cells, double bend) {
  mesh::TetMesh m;
  m.order = order;
  const int scale = order; // lattice step = 1 / (cells * order)
  std::map<std::array<int, 3>, int> node_of;
  auto node = [&](const std::array<int, 3>& key) {
    auto [it, inserted] = node_of.emplace(key, static_cast<int>(m.nodes.size()));
    if (inserted) {
      const double h = 1.0 / (cells * scale);
      Eigen::Vector3d x(key[0] * h, key[1] * h, key[2] * h);
      const double pi = std::numbers::pi;
      Eigen::Vector3d d(std::sin(pi * x.y()) * std::sin(pi * x.z()), std::sin(pi * x.z()) * std::sin(pi * x.x()),
                        std::sin(pi * x.x()) * std::sin(pi * x.y()));
      m.nodes.push_back(x + bend / pi * d);
    }
    return it->second;
  };
  // Kuhn: for each permutation (a, b, c) the tet 0, e_a, e_a+e_b, 1.
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const bool odd[6] = {false, true, true, false, false, true};
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      for (int k = 0; k < cells; ++k)
        for (int p = 0; p < 6; ++p) {
          std::array<std::array<int, 3>, 4> v;
          v[0] = {i, j, k};
          v[1] = v[0];
          v[1][perms[p][0]] += 1;
          v[2] = v[1];
          v[2][perms[p][1]] += 1;
          v[3] = {i + 1, j + 1, k + 1};
          if (odd[p]) std::swap(v[1], v[2]); // make orient3d > 0
          for (int n = 0; n < highorder::tet_node_count(order); ++n) {
            auto q = highorder::tet_node(order, n);
            const int l[4] = {order - q[0] - q[1] - q[2], q[0], q[1], q[2]};
            std::array<int, 3> key{0, 0, 0};
            for (int c = 0; c < 4; ++c)
              for (int d = 0; d < 3; ++d) key[d] += l[c] * v[c][d];
            m.tets.push_back(node(key));
          }
        }
  // Boundary: faces (by sorted corners) used once.
  std::map<std::array<int, 3>, std::pair<int, int>> faces; // sorted corners -> (tet, face), count via erase
  for (int t = 0; t < m.num_tets(); ++t)
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> c;
      for (int k = 0; k < 3; ++k) c[k] = m.tet(t)[highorder::kTetFaces[f][k]];
      std::sort(c.begin(), c.end());
      auto [it, inserted] = faces.emplace(c, std::make_pair(t, f));
      if (!inserted) faces.erase(it);
    }
  for (const auto& [key, tf] : faces)
    for (int n : highorder::tet_face_nodes(order, tf.second)) m.boundary.push_back(m.tet(tf.first)[n]);
  mesh::set_default_groups(m);
  return m;
}

} // namespace curvetet::testing

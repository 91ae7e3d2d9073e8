#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/node_ordering.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <map>
#include <set>

using namespace curvetet::highorder;

// Two tets glued on face (1,2,3), listed with different local vertex orders:
//
//        3                 tet A = (0,1,2,3), tet B = (4,3,2,1)
//       /|\                shared: 3 corners, 3 edges, 1 face
//      / | \ .
//     0--|--4
//      \ | /
//       1-2
TEST(ConformingNodes, SharedFaceGetsSharedNodesAndCountsMatchEuler) {
  const std::vector<std::array<int, 4>> tets = {{0, 1, 2, 3}, {4, 3, 2, 1}};
  for (int p = 1; p <= 6; ++p) {
    auto nodes = number_tet_nodes(5, tets, p);
    // V + E(P-1) + F(P-1)(P-2)/2 + T(P-1)(P-2)(P-3)/6 with V=5, E=9, F=7, T=2.
    const int expected = 5 + 9 * (p - 1) + 7 * (p - 1) * (p - 2) / 2 + 2 * (p - 1) * (p - 2) * (p - 3) / 6;
    EXPECT_EQ(nodes.num_nodes, expected) << "order " << p;
    const int n = tet_node_count(p);
    // Every node of A with weight 0 on vertex 0 is also a node of B.
    std::set<int> a(nodes.tet_nodes.begin(), nodes.tet_nodes.begin() + n);
    std::set<int> b(nodes.tet_nodes.begin() + n, nodes.tet_nodes.end());
    std::vector<int> common;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
    EXPECT_EQ(static_cast<int>(common.size()), triangle_node_count(p));
    // Corners keep their vertex ids.
    for (int k = 0; k < 4; ++k) EXPECT_EQ(nodes.tet_nodes[n + k], tets[1][k]);
  }
}

TEST(ConformingNodes, SameGeometricPositionFromBothSides) {
  const std::vector<std::array<int, 4>> tets = {{0, 1, 2, 3}, {4, 3, 2, 1}};
  const int p = 4, n = tet_node_count(p);
  auto nodes = number_tet_nodes(5, tets, p);
  // Place the 5 vertices anywhere; a shared node must get the same point from
  // either tet's barycentric weights.
  const double X[5][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  std::map<int, std::array<double, 3>> placed;
  for (int t = 0; t < 2; ++t)
    for (int i = 0; i < n; ++i) {
      auto w = tet_node_barycentric(p, i);
      std::array<double, 3> x{0, 0, 0};
      for (int k = 0; k < 4; ++k)
        for (int d = 0; d < 3; ++d) x[d] += w[k] * X[tets[t][k]][d];
      auto [it, inserted] = placed.try_emplace(nodes.tet_nodes[t * n + i], x);
      if (!inserted)
        for (int d = 0; d < 3; ++d) EXPECT_NEAR(it->second[d], x[d], 1e-15);
    }
}

// Node orderings: Gmsh's table (internal order) starts with the corners and
// edges in Gmsh's edge walk; VTK permutations are permutations and match the
// documented quadratic layouts; tet faces map to the right nodes.
#include "curvetet/highorder/node_ordering.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <numeric>

using namespace curvetet::highorder;

TEST(NodeOrdering, GmshTetCornersAndEdgeWalk) {
  for (int p = 1; p <= kMaxOrder; ++p) {
    EXPECT_EQ(tet_node(p, 0), (std::array<int, 3>{0, 0, 0}));
    EXPECT_EQ(tet_node(p, 1), (std::array<int, 3>{p, 0, 0}));
    EXPECT_EQ(tet_node(p, 2), (std::array<int, 3>{0, p, 0}));
    EXPECT_EQ(tet_node(p, 3), (std::array<int, 3>{0, 0, p}));
    if (p < 3) continue;
    // Edges 0-1, 1-2, 2-0, 3-0, 3-2, 3-1 each walked from its first vertex.
    const std::array<int, 3> c[4] = {{0, 0, 0}, {p, 0, 0}, {0, p, 0}, {0, 0, p}};
    const int walk[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
    int i = 4;
    for (const auto& e : walk)
      for (int s = 1; s < p; ++s, ++i) {
        std::array<int, 3> q;
        for (int k = 0; k < 3; ++k) q[k] = (c[e[0]][k] * (p - s) + c[e[1]][k] * s) / p;
        EXPECT_EQ(tet_node(p, i), q) << "order " << p << " node " << i;
      }
  }
  EXPECT_EQ(gmsh_tet_type(2), 11);
  EXPECT_EQ(gmsh_tet_type(3), 29);
  EXPECT_EQ(gmsh_tet_type(4), 30);
  EXPECT_EQ(gmsh_tet_type(5), 31);
  EXPECT_EQ(gmsh_triangle_type(4), 23);
  EXPECT_EQ(gmsh_tet_order(71), 6);
}

TEST(NodeOrdering, VtkPermutations) {
  for (int p = 1; p <= kMaxOrder; ++p) {
    auto t = vtk_tet_permutation(p);
    ASSERT_EQ(int(t.size()), tet_node_count(p));
    std::sort(t.begin(), t.end());
    for (int i = 0; i < int(t.size()); ++i) EXPECT_EQ(t[i], i);
    auto s = vtk_triangle_permutation(p);
    ASSERT_EQ(int(s.size()), triangle_node_count(p));
    std::sort(s.begin(), s.end());
    for (int i = 0; i < int(s.size()); ++i) EXPECT_EQ(s[i], i);
  }
  // VTK's 10-node tet: edges 01,12,20,03,13,23; Gmsh's: 01,12,20,30,32,31.
  EXPECT_EQ(vtk_tet_permutation(2), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 9, 8}));
  // Triangles agree between Gmsh and VTK (corners, edges 01 12 20, interior).
  for (int p = 1; p <= kMaxOrder; ++p) {
    std::vector<int> id(triangle_node_count(p));
    std::iota(id.begin(), id.end(), 0);
    EXPECT_EQ(vtk_triangle_permutation(p), id) << p;
  }
  // Order 3 VTK tet: point 16 is the centre of face (0,1,3) (y = 0).
  auto t3 = vtk_tet_permutation(3);
  EXPECT_EQ(tet_node(3, t3[16]), (std::array<int, 3>{1, 0, 1}));
}

TEST(NodeOrdering, TetFacesHaveTheirNodes) {
  for (int p = 1; p <= kMaxOrder; ++p)
    for (int f = 0; f < 4; ++f) {
      const auto& nodes = tet_face_nodes(p, f);
      ASSERT_EQ(int(nodes.size()), triangle_node_count(p));
      for (int c = 0; c < 3; ++c) EXPECT_EQ(nodes[c], kTetFaces[f][c]);
      // Every face node lies on the plane of face f (lambda_f = 0).
      for (int n : nodes) {
        auto q = tet_node(p, n);
        const int lambda[4] = {p - q[0] - q[1] - q[2], q[0], q[1], q[2]};
        EXPECT_EQ(lambda[f], 0);
      }
    }
}

TEST(NodeOrdering, TetLatticeEdgesJoinNeighbouringLatticePoints) {
  for (int order = 1; order <= 6; ++order) {
    const auto& edges = tet_lattice_edges(order);
    // The order-P lattice has P(P+1)(P+2) such edges (6 per unit step of
    // each of the 6 edge directions times the lattice's P(P+1)(P+2)/6 cells).
    EXPECT_EQ(static_cast<int>(edges.size()), order * (order + 1) * (order + 2)) << "order " << order;
    for (const auto& [i, j] : edges) {
      ASSERT_LT(i, j);
      const auto a = tet_node(order, i), b = tet_node(order, j);
      const int d[4] = {b[0] - a[0], b[1] - a[1], b[2] - a[2], -(b[0] - a[0]) - (b[1] - a[1]) - (b[2] - a[2])};
      int plus = 0, minus = 0;
      for (int x : d) {
        ASSERT_LE(std::abs(x), 1);
        plus += x == 1;
        minus += x == -1;
      }
      EXPECT_TRUE(plus == 1 && minus == 1);
    }
  }
}

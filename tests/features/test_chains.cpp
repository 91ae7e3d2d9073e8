#include "curvetet/check/preconditions.hpp"
#include "curvetet/features/chains.hpp"
#include "curvetet/features/detect.hpp"
#include "curvetet/features/refine.hpp"
#include "support/shapes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace curvetet;
using features::group_features;

namespace {

std::vector<std::array<int, 2>> sorted_edges(std::vector<std::array<int, 2>> e) {
  for (auto& x : e)
    if (x[0] > x[1]) std::swap(x[0], x[1]);
  std::sort(e.begin(), e.end());
  return e;
}

// Every feature edge is in exactly one chain/loop.
void expect_partition(const features::FeatureGraph& g, const std::vector<std::array<int, 2>>& edges) {
  std::vector<std::array<int, 2>> seen;
  for (const auto& c : g.chains) {
    const int n = static_cast<int>(c.vertices.size());
    for (int i = 0; i < c.num_edges(); ++i) seen.push_back({c.vertices[i], c.vertices[(i + 1) % n]});
  }
  EXPECT_EQ(sorted_edges(seen), edges);
}

// Open cylinder side between two n-gon rims, closed by two fans: rims are
// feature loops, nothing else.
mesh::SurfaceMesh cylinder(int n) {
  mesh::SurfaceMesh m;
  for (int z = 0; z < 2; ++z)
    for (int i = 0; i < n; ++i) {
      double a = 2 * std::numbers::pi * i / n;
      m.vertices.emplace_back(std::cos(a), std::sin(a), z);
    }
  const int bottom_c = 2 * n, top_c = 2 * n + 1;
  m.vertices.emplace_back(0, 0, 0);
  m.vertices.emplace_back(0, 0, 1);
  for (int i = 0; i < n; ++i) {
    int j = (i + 1) % n;
    m.faces.push_back({i, j, n + j});
    m.faces.push_back({i, n + j, n + i});
    m.faces.push_back({bottom_c, j, i});
    m.faces.push_back({top_c, n + i, n + j});
  }
  return m;
}

} // namespace

TEST(FeatureChains, CubeHas12ChainsAnd8Corners) {
  auto m = test::cube();
  auto edges = features::detect_feature_edges(m, mesh::build_edge_topology(m.faces), 30.0);
  auto g = group_features(m.num_vertices(), edges, {});
  EXPECT_EQ(g.corners.size(), 8u);
  ASSERT_EQ(g.chains.size(), 12u);
  for (const auto& c : g.chains) {
    EXPECT_FALSE(c.closed);
    EXPECT_EQ(c.num_edges(), 1);
  }
  expect_partition(g, edges);
}

TEST(FeatureChains, CylinderHasTwoLoops) {
  auto m = cylinder(12);
  ASSERT_TRUE(check::check_preconditions(mesh::to_soup(m)).ok());
  auto edges = features::detect_feature_edges(m, mesh::build_edge_topology(m.faces), 60.0);
  ASSERT_EQ(edges.size(), 24u);
  auto g = group_features(m.num_vertices(), edges, {});
  EXPECT_TRUE(g.corners.empty());
  ASSERT_EQ(g.chains.size(), 2u);
  for (const auto& c : g.chains) {
    EXPECT_TRUE(c.closed);
    EXPECT_EQ(c.num_edges(), 12);
  }
  expect_partition(g, edges);
  // A user corner opens a loop into a chain from that corner back to itself.
  auto g2 = group_features(m.num_vertices(), edges, {3});
  ASSERT_EQ(g2.chains.size(), 2u);
  EXPECT_FALSE(g2.chains[0].closed);
  EXPECT_EQ(g2.chains[0].vertices.front(), 3);
  EXPECT_EQ(g2.chains[0].vertices.back(), 3);
  EXPECT_EQ(g2.chains[0].num_edges(), 12);
}

TEST(FeatureChains, TJunction) {
  //   0 - 1 - 2 - 3 - 4        corners: 0, 4, 6 (chain ends) and 2 (three
  //           |                chains meet); chains 2-1-0, 2-3-4, 2-5-6.
  //           5
  //           |
  //           6
  std::vector<std::array<int, 2>> edges = sorted_edges({{0, 1}, {1, 2}, {2, 3}, {3, 4}, {2, 5}, {5, 6}});
  auto g = group_features(7, edges, {});
  EXPECT_EQ(g.corners, (std::vector<int>{0, 2, 4, 6}));
  ASSERT_EQ(g.chains.size(), 3u);
  EXPECT_EQ(g.chains[0].vertices, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(g.chains[1].vertices, (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(g.chains[2].vertices, (std::vector<int>{2, 5, 6}));
  expect_partition(g, edges);
}

TEST(FeatureRefinement, SplitsFacesWithTwoFeatureEdges) {
  auto m = test::cube();
  auto edges = features::detect_feature_edges(m, mesh::build_edge_topology(m.faces), 30.0);
  auto r = features::refine_multi_feature_faces(m, edges);
  EXPECT_EQ(r.mesh.num_faces(), 36); // every cube triangle has two cube edges
  EXPECT_EQ(r.mesh.num_vertices(), 8 + 12);
  EXPECT_EQ(r.parent_of_new_vertex.size(), 12u);
  ASSERT_EQ(r.parent_face.size(), 36u);
  auto check = check::check_preconditions(mesh::to_soup(r.mesh));
  EXPECT_TRUE(check.ok()) << check.text();
  auto topo = mesh::build_edge_topology(r.mesh.faces);
  for (const auto& e : edges) EXPECT_TRUE(std::binary_search(topo.edges.begin(), topo.edges.end(), e));
  for (const auto& f : r.mesh.faces) {
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      std::array<int, 2> e{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])};
      count += std::binary_search(edges.begin(), edges.end(), e);
    }
    EXPECT_LE(count, 1);
  }
}

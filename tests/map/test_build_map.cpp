// The map built from a real pipeline run: it covers every input vertex and
// every boundary node; each input vertex's image lies within epsilon (the
// guarantee, DESIGN.md invariant 4, holds for the input vertices); a node's
// preimage lies on the node's fiber, inside its prism (not bound by epsilon:
// invariant 4 is not checked between input vertices); the boundary side
// matches the written mesh.
#include "map_fixture.hpp"

#include "curvetet/highorder/element_map.hpp"
#include "curvetet/map/transfer.hpp"

#include <gtest/gtest.h>

using namespace curvetet;

class BuildMap : public ::testing::TestWithParam<double> {};

TEST_P(BuildMap, ImagesStayWithinEpsilon) {
  const auto& r = test::mapped_ellipsoid(GetParam());
  ASSERT_TRUE(r.result.verification.ok());
  const auto& m = r.map;
  ASSERT_EQ(m.vertex_to_boundary.size(), m.input.vertices.size());
  ASSERT_EQ(m.num_triangles(), r.result.mesh.num_boundary());
  double worst_forward = 0, worst_backward = 0;
  for (std::size_t i = 0; i < m.input.vertices.size(); ++i) {
    const auto& p = m.vertex_to_boundary[i];
    EXPECT_GE(p.u, -1e-12);
    EXPECT_GE(p.v, -1e-12);
    EXPECT_LE(p.u + p.v, 1 + 1e-12);
    worst_forward = std::max(worst_forward, (map::boundary_point(m, p) - m.input.vertices[i]).norm());
  }
  for (std::size_t j = 0; j < m.nodes.size(); ++j) {
    const auto& p = m.node_to_input[j];
    EXPECT_GE(std::min({p.u, p.v, 1 - p.u - p.v}), -1e-15);
    worst_backward = std::max(worst_backward, (map::input_point(m, p) - m.nodes[j]).norm());
  }
  EXPECT_LT(worst_forward, r.epsilon_abs);
  double prism_diameter = 0;
  const auto& sh = r.result.shell;
  for (const auto& f : sh.faces)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        prism_diameter = std::max({prism_diameter, (sh.top[f[a]] - sh.bottom[f[b]]).norm(),
                                   (sh.top[f[a]] - sh.middle[f[b]]).norm(), (sh.middle[f[a]] - sh.bottom[f[b]]).norm()});
  EXPECT_LT(worst_backward, prism_diameter);
  std::printf("eps %.3g: input vertex -> image max %.3g eps, boundary node -> preimage max %.3g eps\n", GetParam(),
              worst_forward / r.epsilon_abs, worst_backward / r.epsilon_abs);
  // The map is not the identity: the coarse boundary really moved away.
  EXPECT_GT(worst_backward, 0.05 * r.epsilon_abs);
}

// Boundary triangle b of the map is the mesh's boundary triangle b, node for
// node, and its curved evaluation at a lattice point is that node.
TEST_P(BuildMap, BoundaryMatchesTheMesh) {
  const auto& r = test::mapped_ellipsoid(GetParam());
  const auto& m = r.map;
  const auto& mesh = r.result.mesh;
  ASSERT_EQ(m.order, mesh.order);
  for (int b = 0; b < mesh.num_boundary(); ++b)
    for (int i = 0; i < mesh.triangle_nodes(); ++i) {
      const int j = m.triangle(b)[i];
      EXPECT_EQ(m.node_ids[j], mesh.boundary_triangle(b)[i]);
      EXPECT_EQ(m.nodes[j], mesh.nodes[m.node_ids[j]]);
    }
  std::vector<mesh::Vec3> corners(m.triangle_nodes());
  for (int i = 0; i < m.triangle_nodes(); ++i) corners[i] = m.nodes[m.triangle(0)[i]];
  const auto at = highorder::triangle_point(m.order, corners.data(), Eigen::Vector2d(1.0 / 3, 1.0 / 3));
  EXPECT_LT((map::boundary_point(m, {0, 1.0 / 3, 1.0 / 3}) - at).norm(), 1e-12);
  EXPECT_EQ(r.stats.nodes, static_cast<int>(m.nodes.size()));
}

INSTANTIATE_TEST_SUITE_P(Ellipsoid, BuildMap, ::testing::Values(0.02, 0.01));

// A shell with a singular (pinched) vertex: its slab tets with a zero pillar
// are left out, yet every shell face still has its boundary triangle (else
// build_boundary_map throws) and the map sends every input vertex within
// epsilon.
TEST(BuildMapPinched, FoldedStar) {
  const auto input = shell::test::folded_star();
  pipeline::PipelineOptions o;
  o.epsilon = 0.02;
  Report report;
  const auto r = pipeline::run_pipeline(input, o, report);
  ASSERT_GT(report["shell"]["singular_vertices"].get<int>(), 0);
  ASSERT_TRUE(r.verification.ok()) << r.verification.text();
  const auto m = map::build_boundary_map(r.shell, r.mesh);
  const double eps = 0.02 * mesh::bbox_diagonal(input.vertices);
  for (std::size_t i = 0; i < m.input.vertices.size(); ++i)
    EXPECT_LT((map::boundary_point(m, m.vertex_to_boundary[i]) - m.input.vertices[i]).norm(), eps);
  EXPECT_EQ(m.num_triangles(), r.shell.num_prisms());
  EXPECT_EQ(m.node_to_input.size(), m.nodes.size());
}

// Whole-mesh verifier: a valid curved box passes every check; each defect
// (an inverted tet, a missing / flipped boundary triangle, a self-
// intersecting boundary, an input too far away) is reported and fails it.
#include "curvetet/check/boundary_linearization.hpp"
#include "curvetet/check/verify_tet_mesh.hpp"
#include "curvetet/check/closest_points.hpp"
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/node_ordering.hpp"

#include "common/curved_box.hpp"

#include <gtest/gtest.h>

using namespace curvetet;

TEST(VerifyTetMesh, ValidCurvedBoxPasses) {
  for (int order : {1, 2, 3, 4}) {
    auto m = curvetet::testing::curved_box(order, 2, 0.3);
    auto v = check::verify_tet_mesh(m);
    EXPECT_TRUE(v.ok()) << v.text();
    EXPECT_EQ(v.positive, m.num_tets());
    EXPECT_GT(v.min_det_lower_bound, 0);
    EXPECT_LE(v.min_det_lower_bound, v.min_det_upper_bound);
    EXPECT_GT(v.worst_scaled_jacobian, 0);
    EXPECT_EQ(v.linearized_faces, std::size_t(m.num_boundary()) * 4 * order * order);
    EXPECT_TRUE(v.surface.ok());
  }
}

TEST(VerifyTetMesh, InvertedTetFails) {
  auto m = curvetet::testing::curved_box(4, 2, 0.3);
  // Node 34 of tet 0 is its interior node (order 4): move it out of the tet.
  m.nodes[m.tet(0)[34]] += Eigen::Vector3d(3, 3, 3);
  auto v = check::verify_tet_mesh(m);
  EXPECT_FALSE(v.ok());
  EXPECT_GE(v.invalid + v.undecided, 1u);
  ASSERT_FALSE(v.invalid_examples.empty());
  EXPECT_EQ(v.invalid_examples[0], 0);
  EXPECT_TRUE(v.conformity_ok());
}

TEST(VerifyTetMesh, MissingAndFlippedBoundaryFail) {
  auto m = curvetet::testing::curved_box(2, 1, 0.2);
  auto missing = m;
  missing.boundary.resize(missing.boundary.size() - missing.triangle_nodes());
  missing.boundary_tags.pop_back();
  auto v = check::verify_tet_mesh(missing);
  EXPECT_EQ(v.boundary_missing, 1u);
  EXPECT_FALSE(v.surface.ok()); // open
  EXPECT_FALSE(v.ok());

  auto flipped = m;
  int* tri = flipped.boundary.data();
  // Reverse the orientation: swap corners 1 and 2 and the edge nodes accordingly.
  std::swap(tri[1], tri[2]);
  auto w = check::verify_tet_mesh(flipped);
  EXPECT_EQ(w.boundary_flipped, 1u);
  EXPECT_FALSE(w.ok());

  auto other_nodes = m;
  std::swap(other_nodes.boundary[3], other_nodes.boundary[4]); // two edge nodes of the first triangle
  auto x = check::verify_tet_mesh(other_nodes);
  EXPECT_EQ(x.boundary_node_mismatch, 1u);
  EXPECT_FALSE(x.ok());
}

TEST(VerifyTetMesh, OverlappingComponentsSelfIntersect) {
  auto a = curvetet::testing::curved_box(2, 1, 0.1);
  auto b = a;
  const int offset = static_cast<int>(a.nodes.size());
  for (auto& p : b.nodes) a.nodes.push_back(p + Eigen::Vector3d(0.5, 0.31, 0.27));
  for (int id : b.tets) a.tets.push_back(id + offset);
  for (int id : b.boundary) a.boundary.push_back(id + offset);
  mesh::set_default_groups(a);
  auto v = check::verify_tet_mesh(a);
  EXPECT_TRUE(v.positivity_ok());
  EXPECT_TRUE(v.conformity_ok());
  EXPECT_FALSE(v.surface.ok());
  bool self = false;
  for (const auto& d : v.surface.defects) self |= d.kind == InputDefect::self_intersection;
  EXPECT_TRUE(self) << v.text();
}

TEST(VerifyTetMesh, DistanceToInput) {
  auto m = curvetet::testing::curved_box(3, 2, 0.3);
  // The input: a finer linearization of the same curved boundary.
  auto input = check::linearize_boundary(m, 9).surface;
  check::TetMeshVerifyOptions o;
  o.input = &input;
  auto v = check::verify_tet_mesh(m, o);
  EXPECT_TRUE(v.ok()) << v.text();
  EXPECT_LT(v.input_to_boundary_max, 1e-3);
  EXPECT_LT(v.boundary_to_input_max, 1e-3);
  for (auto& p : input.vertices) p += Eigen::Vector3d(0.05, 0, 0);
  auto w = check::verify_tet_mesh(m, o);
  EXPECT_FALSE(w.distance_ok());
  EXPECT_GT(w.input_to_boundary_max, 0.01);
  EXPECT_FALSE(w.ok());
}

TEST(VerifyTetMesh, DistanceIsMeasuredOnTheCurvedSurfaceNotOnItsChords) {
  // Points of the curved boundary itself, inside its triangles: distance 0.
  // The flat linearization with one segment per edge is the triangle of the
  // corners, which the bulge leaves far behind.
  auto m = curvetet::testing::curved_box(3, 2, 0.3);
  mesh::SurfaceMesh input;
  for (int b = 0; b < m.num_boundary(); ++b) {
    std::vector<Eigen::Vector3d> nodes;
    for (int k = 0; k < m.triangle_nodes(); ++k) nodes.push_back(m.nodes[m.boundary_triangle(b)[k]]);
    for (const Eigen::Vector2d uv : {Eigen::Vector2d(0.3, 0.3), Eigen::Vector2d(0.2, 0.5), Eigen::Vector2d(0.6, 0.1)})
      input.vertices.push_back(highorder::triangle_point(3, nodes.data(), uv));
    const int n = static_cast<int>(input.vertices.size());
    input.faces.push_back({n - 3, n - 2, n - 1});
  }
  const auto chords = check::linearize_boundary(m, 1);
  double chord_max = 0;
  for (double d : check::distances_to_surface(chords.surface, input.vertices)) chord_max = std::max(chord_max, d);
  ASSERT_GT(chord_max, 0.01);

  check::TetMeshVerifyOptions o;
  o.input = &input;
  o.segments_per_edge = 1;
  o.epsilon = 1e-9;
  const auto v = check::verify_tet_mesh(m, o);
  EXPECT_LT(v.input_to_boundary_max, 1e-12) << "chord distance " << chord_max;
  EXPECT_TRUE(v.input_to_boundary_ok());
  // The input is a small triangle inside each boundary triangle: the rest of
  // the boundary is far from it, and ε both ways fails on that direction.
  EXPECT_FALSE(v.boundary_to_input_ok());
  EXPECT_FALSE(v.distance_ok());
  EXPECT_FALSE(v.ok());
  EXPECT_NE(v.text().find("FAIL (boundary->input exceeds epsilon)"), std::string::npos) << v.text();
  EXPECT_EQ(v.json()["distance"]["boundary_to_input_ok"], false);
}

// The curved boundary certificate: it settles every pair of a valid curved
// boundary (shared edges, shared corners, near but apart), and it rejects
// curved patches that touch or fold where the flat linearization sees
// nothing wrong.
#include "curvetet/check/bezier_patch.hpp"
#include "curvetet/check/boundary_linearization.hpp"
#include "curvetet/check/curved_boundary_certificate.hpp"
#include "curvetet/check/patch_separation.hpp"
#include "curvetet/check/self_intersection.hpp"
#include "curvetet/highorder/element_map.hpp"

#include "common/curved_box.hpp"

#include <gtest/gtest.h>

using namespace curvetet;
using Eigen::Vector3d;

namespace {

// A mesh of quadratic boundary triangles only (the certificate reads no tets).
// Each triangle: three corners, then the nodes on edges 0-1, 1-2, 2-0.
mesh::TetMesh quadratic_triangles(const std::vector<std::array<Vector3d, 6>>& triangles) {
  mesh::TetMesh m;
  m.order = 2;
  for (const auto& t : triangles)
    for (const auto& x : t) {
      m.boundary.push_back(static_cast<int>(m.nodes.size()));
      m.nodes.push_back(x);
    }
  return m;
}

// Corners at height h and edge nodes at height h / 4 over a flat triangle:
// z = (h / 2)(3 Σλ² - 1) ≥ 0, zero at the centroid only, which is not a
// point of the order-4 linearization lattice.
std::array<Vector3d, 6> sagging_triangle(double h) {
  const Vector3d a(0.125, 0.125, h), b(0.625, 0.125, h), c(0.125, 0.625, h);
  auto mid = [&](const Vector3d& p, const Vector3d& q) { return Vector3d(0.5 * (p.x() + q.x()), 0.5 * (p.y() + q.y()), h / 4); };
  return {a, b, c, mid(a, b), mid(b, c), mid(c, a)};
}

std::array<Vector3d, 6> flat_triangle() {
  return {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0),
          Vector3d(0.5, 0, 0), Vector3d(0.5, 0.5, 0), Vector3d(0, 0.5, 0)};
}

} // namespace

TEST(CurvedBoundaryCertificate, CurvedBoxIsCertified) {
  for (int order : {1, 2, 3, 4}) {
    const auto m = curvetet::testing::curved_box(order, 2, 0.3);
    const auto c = check::certify_curved_boundary(m);
    EXPECT_TRUE(c.ok()) << "order " << order << ": " << c.unsettled.size() << " unsettled, first ("
                        << (c.ok() ? -1 : c.unsettled[0].first) << ", " << (c.ok() ? -1 : c.unsettled[0].second) << ")";
    EXPECT_EQ(c.patches, std::size_t(m.num_boundary()));
    // Every triangle overlaps at least its three edge neighbours.
    EXPECT_GE(c.pairs, 3 * c.patches / 2);
  }
}

TEST(CurvedBoundaryCertificate, TouchingPatchesAreRejectedWhereTheLinearizationSeesNothing) {
  // The sagging patch touches the flat one at one point (its centroid's
  // height is exactly 0); no vertex of its order-4 linearization does.
  const auto m = quadratic_triangles({flat_triangle(), sagging_triangle(0.125)});
  const auto flat = check::linearize_boundary(m, 4);
  EXPECT_TRUE(check::self_intersections(flat.surface).empty());
  const auto centroid = highorder::triangle_point(2, m.nodes.data() + 6, Eigen::Vector2d(1.0 / 3, 1.0 / 3));
  EXPECT_NEAR(centroid.z(), 0.0, 1e-15);

  const auto c = check::certify_curved_boundary(m);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.unsettled, (std::vector<std::pair<int, int>>{{0, 1}}));

  // Lifted by 1/64 the two are apart: settled, after splitting near the
  // closest point.
  auto apart = sagging_triangle(0.125);
  for (auto& x : apart) x.z() += 1.0 / 64;
  const auto d = check::certify_curved_boundary(quadratic_triangles({flat_triangle(), apart}));
  EXPECT_TRUE(d.ok());
  EXPECT_GT(d.deepest, 0);
}

TEST(CurvedBoundaryCertificate, FoldedPatchIsRejected) {
  // A flat quadratic triangle whose edge 1-2 node is pulled past corner 0:
  // the patch covers part of the plane twice.
  auto t = flat_triangle();
  t[4] = Vector3d(-0.6, -0.6, 0);
  const auto c = check::certify_curved_boundary(quadratic_triangles({t}));
  EXPECT_EQ(c.unsettled, (std::vector<std::pair<int, int>>{{0, 0}}));
  EXPECT_TRUE(check::certify_curved_boundary(quadratic_triangles({flat_triangle()})).ok());
}

TEST(CurvedBoundaryCertificate, PiecesKeepTheRootsCornersExactly) {
  const auto m = curvetet::testing::curved_box(4, 1, 0.3);
  std::vector<Vector3d> nodes;
  for (int i = 0; i < m.triangle_nodes(); ++i) nodes.push_back(m.nodes[m.boundary_triangle(0)[i]]);
  const auto root = check::root_patch(4, nodes);
  EXPECT_GT(root.radius, 0);
  const auto pieces = check::split_patch(root, root);
  for (int v = 0; v < 3; ++v) {
    EXPECT_EQ(pieces[v].corner(v), root.corner(v)); // bitwise: a root corner is copied
    EXPECT_EQ(root.corner(v), nodes[v]);
  }
  // A piece's corners are points of the patch: the middle piece's corner 0
  // is the midpoint of edge 1-2.
  const auto mid12 = highorder::triangle_point(4, nodes.data(), Eigen::Vector2d(0.5, 0.5));
  EXPECT_LE((pieces[3].corner(0) - mid12).norm(), 1e-14);
  // Adjacent pieces meet only where they share, by the proofs themselves.
  EXPECT_TRUE(check::meet_only_along_edge(pieces[0], 1, 2, pieces[3], 2, 1));
  EXPECT_TRUE(check::meet_only_at_corner(pieces[0], 1, pieces[1], 0));
}

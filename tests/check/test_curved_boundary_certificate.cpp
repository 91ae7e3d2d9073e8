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

TEST(PatchSeparation, ThinPiecesSideBySideInATiltedPlaneAreApart) {
  // Slivers in the plane x = z along the diagonal s = t, 0.01 apart across
  // it: their boxes overlap at every size, an in-plane axis separates them.
  auto on_plane = [](double s, double t) { return Vector3d(s, t, s); };
  const std::vector<Vector3d> a{on_plane(0, 0), on_plane(1, 0.99), on_plane(1, 1)};
  const std::vector<Vector3d> b{on_plane(0, 0.01), on_plane(1, 1.01), on_plane(0, 0.02)};
  const auto pa = check::root_patch(1, a), pb = check::root_patch(1, b);
  EXPECT_TRUE(geometry::boxes_overlap(pa.box(), pb.box()));
  EXPECT_TRUE(check::apart(pa, pb));
  // Moved across the diagonal, b crosses a: no axis may claim otherwise.
  const std::vector<Vector3d> crossing{on_plane(0.5, 0.49), on_plane(1, 1.01), on_plane(0, 0.02)};
  EXPECT_FALSE(check::apart(pa, check::root_patch(1, crossing)));
}

TEST(CurvedBoundaryCertificate, WigglyEdgePatchIsCertified) {
  // A boundary triangle of the main job's output on couplingdown (P = 4):
  // its edge 2-0 wiggles by 4e-5 and the speed along it varies 20 times, so
  // pieces near the edge are slivers side by side (boxes alone never parted
  // them), and one corner's 28 directions sit within a few degrees (the
  // linear program's default pricing cycled there).
  mesh::TetMesh m;
  m.order = 4;
  m.nodes = {{0.49213800000000002, 1.5455999999999999e-09, -0.18239},
             {0.48961300000000002, 0.049788100000000002, -0.18239},
             {0.5, 0, -0.17452799999999999},
             {0.49329359467649103, 0.012817341527740795, -0.18068464963012013},
             {0.49099410984925113, 0.024921019393034299, -0.18227658160991095},
             {0.48863532009738575, 0.037011212948210664, -0.18392522278474632},
             {0.49220974999999995, 0.037341075000000001, -0.18042449999999999},
             {0.49480649999999998, 0.024894050000000001, -0.17845900000000001},
             {0.49740325000000013, 0.012447025, -0.17649350000000003},
             {0.49663901265942911, 4.2835867214198489e-05, -0.17788312532609674},
             {0.49606899975471908, 7.7864231688972449e-10, -0.17845900016929805},
             {0.49549898697264955, -4.2834312850723148e-05, -0.17903487492785036},
             {0.496176218421854, 0.01266177723997192, -0.17856851225890857},
             {0.4939478812379357, 0.024889687742012116, -0.18011191166783386},
             {0.49661577875861684, 0.012566895381679963, -0.17809787918161735}};
  for (int i = 0; i < 15; ++i) m.boundary.push_back(i);
  const auto c = check::certify_curved_boundary(m);
  EXPECT_TRUE(c.ok());
  EXPECT_GT(c.deepest, 4);
}

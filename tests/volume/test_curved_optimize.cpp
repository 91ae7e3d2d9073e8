// Curved optimization: lowers the max AMIPS, never moves a boundary node,
// and keeps every tet certified positive.
#include "curvetet/check/verify_tet_mesh.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/volume/curved_optimize.hpp"
#include "curvetet/volume/curved_remesh.hpp"
#include "flat_inner_tet.hpp"
#include "straight_mesh.hpp"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace curvetet;
using mesh::Vec3;

TEST(CurvedOptimize, LowersMaxAmipsAndKeepsTheBoundaryAndPositivity) {
  for (int order : {3, 4}) {
    SCOPED_TRACE(order);
    auto m = test::flat_inner_tet_mesh(order);
    ASSERT_TRUE(check::verify_tet_mesh(m).ok());
    const auto before = m;
    volume::CurvedOptimizeOptions o;
    o.bad_fraction = 1.0; // visit every tet above min_amips
    const auto stats = volume::optimize_curved(m, o);
    EXPECT_GT(stats.vertex_moves + stats.node_moves, 0);
    EXPECT_LT(stats.max_amips_after, 0.8 * stats.max_amips_before)
        << stats.max_amips_before << " -> " << stats.max_amips_after;
    // The boundary nodes are bit-identical.
    for (int id : m.boundary) EXPECT_EQ(m.nodes[id], before.nodes[id]) << "node " << id;
    EXPECT_EQ(m.tets, before.tets);
    EXPECT_EQ(m.boundary, before.boundary);
    const auto v = check::verify_tet_mesh(m);
    EXPECT_TRUE(v.ok()) << v.text();
    EXPECT_NEAR(v.worst_amips, stats.max_amips_after, 1e-9 * stats.max_amips_after);
  }
}

TEST(CurvedOptimize, NothingMovesWhenEveryNodeIsOnTheBoundary) {
  // One order-3 tet with its four faces listed: all 20 nodes lie on them.
  mesh::TetMesh m;
  m.order = 3;
  for (int i = 0; i < m.tet_nodes(); ++i) {
    auto q = highorder::tet_node(3, i);
    m.nodes.push_back(Vec3(q[0] + 2.0 * q[1], 0.3 * q[1], 0.1 * q[2]) / 3.0); // flat-ish: high AMIPS
    m.tets.push_back(i);
  }
  for (int f = 0; f < 4; ++f)
    for (int n : highorder::tet_face_nodes(3, f)) m.boundary.push_back(n);
  const auto before = m.nodes;
  volume::CurvedOptimizeOptions o;
  o.min_amips = 0;
  const auto stats = volume::optimize_curved(m, o);
  EXPECT_EQ(stats.vertex_moves + stats.node_moves, 0);
  EXPECT_EQ(m.nodes, before);
  EXPECT_EQ(stats.max_amips_before, stats.max_amips_after);
}

TEST(CurvedOptimize, UnlistedHullStaysPutToo) {
  // The same mesh without its boundary list: the faces used once are frozen.
  auto m = test::flat_inner_tet_mesh(3);
  const auto listed = m.boundary;
  m.boundary.clear();
  m.boundary_tags.clear();
  const auto before = m.nodes;
  volume::CurvedOptimizeOptions o;
  o.bad_fraction = 1.0;
  const auto stats = volume::optimize_curved(m, o);
  EXPECT_GT(stats.vertex_moves + stats.node_moves, 0);
  for (int id : listed) EXPECT_EQ(m.nodes[id], before[id]) << "node " << id;
}

TEST(CurvedOptimize, ScaledJacobianSweepRaisesTheMinWithoutRaisingTheMaxAmips) {
  auto m = test::flat_inner_tet_mesh(4);
  volume::CurvedOptimizeOptions o;
  o.min_amips = std::numeric_limits<double>::infinity(); // no AMIPS sweep: only the scaled-Jacobian one
  o.min_scaled_jacobian = 0.5;
  o.raise_scaled_jacobian_below = 0.5;
  const auto stats = volume::optimize_curved(m, o);
  EXPECT_GT(stats.scaled_jacobian_moves, 0);
  EXPECT_EQ(stats.scaled_jacobian_moves, stats.vertex_moves + stats.node_moves);
  EXPECT_GT(stats.min_scaled_jacobian_after, 1.5 * stats.min_scaled_jacobian_before)
      << stats.min_scaled_jacobian_before << " -> " << stats.min_scaled_jacobian_after;
  EXPECT_LE(stats.max_amips_after, stats.max_amips_before * (1 + 1e-9));
  const auto v = check::verify_tet_mesh(m);
  EXPECT_TRUE(v.ok()) << v.text();
}

TEST(CurvedOptimize, FrameCacheSizeDoesNotChangeTheResult) {
  auto a = test::flat_inner_tet_mesh(4), b = a;
  volume::CurvedOptimizeOptions o;
  o.bad_fraction = 1.0;
  volume::optimize_curved(a, o);
  o.frame_cache_bytes = 0; // the smallest cache: released and refilled all along
  volume::optimize_curved(b, o);
  EXPECT_EQ(a.nodes, b.nodes);
}

TEST(CurvedOptimize, ThreadCountDoesNotChangeTheResult) {
  auto a = test::flat_inner_tet_mesh(4), b = a;
  volume::CurvedOptimizeOptions o;
  o.bad_fraction = 1.0;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    volume::optimize_curved(a, o);
  }
  {
    tbb::global_control four(tbb::global_control::max_allowed_parallelism, 4);
    volume::optimize_curved(b, o);
  }
  EXPECT_EQ(a.nodes, b.nodes);
}

TEST(CurvedOptimize, SweepCapVisitsOnlyTheWorstTets) {
  auto all = test::flat_inner_tet_mesh(4), capped = all;
  volume::CurvedOptimizeOptions o;
  o.bad_fraction = 1.0;
  const auto full = volume::optimize_curved(all, o);
  o.max_bad_tets = 1; // only the worst tet's nodes are candidates in each sweep
  const auto one = volume::optimize_curved(capped, o);
  EXPECT_GT(one.vertex_moves + one.node_moves, 0);
  EXPECT_LT(one.vertex_moves + one.node_moves, full.vertex_moves + full.node_moves);
  EXPECT_LT(one.max_amips_after, one.max_amips_before);
  const auto v = check::verify_tet_mesh(capped);
  EXPECT_TRUE(v.ok()) << v.text();
}

// The remesh previews candidates in parallel on replicas of its editor:
// the same operations, hence the same mesh, for any thread count.
TEST(CurvedRemesh, ThreadCountDoesNotChangeTheResult) {
  auto a = test::flat_inner_tet_mesh(4), b = a;
  volume::CurvedRemeshOptions o;
  o.target_amips = 3.5; // visit nearly every tet
  volume::CurvedRemeshStats sa, sb;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    sa = volume::remesh_curved(a, o);
  }
  {
    tbb::global_control four(tbb::global_control::max_allowed_parallelism, 4);
    sb = volume::remesh_curved(b, o);
  }
  EXPECT_GT(sa.collapses + sa.flips_2_3 + sa.flips_3_2 + sa.flips_4_4 + sa.edge_removals + sa.splits, 0);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.nodes, b.nodes);
  const auto v = check::verify_tet_mesh(b);
  EXPECT_TRUE(v.ok()) << v.text();
}

// An order-1 mesh of these tets (each turned positive) and outward boundary triangles.
mesh::TetMesh linear_mesh(std::vector<Vec3> nodes, const std::vector<std::array<int, 4>>& tets,
                          std::vector<int> boundary) {
  mesh::TetMesh m;
  m.order = 1;
  m.nodes = std::move(nodes);
  for (auto t : tets) {
    if (geometry::orient3d(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]) < 0) std::swap(t[0], t[1]);
    m.tets.insert(m.tets.end(), t.begin(), t.end());
  }
  m.boundary = std::move(boundary);
  m.tet_tags.assign(tets.size(), mesh::kDomainTag);
  m.boundary_tags.assign(m.boundary.size() / 3, mesh::kBoundaryTag);
  mesh::set_default_groups(m);
  return m;
}

// A roof over a pyramid: the ridge (a, b) 0.01 above the eaves (c, d), apex
// e below. The tet (a, b, c, d) has both roof triangles as boundary faces
// (an ear, AMIPS 54) and all its corners on the boundary: no collapse or
// smoothing can reshape it, only a vertex on its one interior edge (c, d).
mesh::TetMesh roof_with_an_ear() {
  const int a = 0, b = 1, c = 2, d = 3, e = 4;
  // Outward: the roof up, the sides away from the pyramid's axis.
  return linear_mesh({Vec3(-1, 0, 0.01), Vec3(1, 0, 0.01), Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(0, 0, -1.2)},
                     {{a, b, c, d}, {a, c, d, e}, {b, c, d, e}},
                     {a, c, b, a, b, d, a, e, c, c, e, b, b, e, d, d, e, a});
}

TEST(CurvedRemesh, SplitsAnEarThatOnlyANewVertexCanFix) {
  volume::CurvedRemeshOptions o;
  o.flip = o.smooth = o.descend = false; // the splits alone (every vertex is frozen: no collapse)
  {
    auto m = roof_with_an_ear();
    ASSERT_TRUE(check::verify_tet_mesh(m).ok()) << check::verify_tet_mesh(m).text();
    const auto s = volume::remesh_curved(m, o);
    EXPECT_GT(s.max_amips_before, 50);
    EXPECT_GE(s.splits, 1);
    EXPECT_LT(s.max_amips_after, o.ear_split_amips);
    const auto v = check::verify_tet_mesh(m);
    EXPECT_TRUE(v.ok()) << v.text();
  }
  {
    auto m = roof_with_an_ear();
    o.ear_split_amips = std::numeric_limits<double>::infinity(); // ears split only above split_amips, as tets
    const auto s = volume::remesh_curved(m, o);
    EXPECT_EQ(s.splits, 0);
    EXPECT_GT(s.max_amips_after, 50);
  }
}

// The roof with an ear at order 4, the ridge 0.003 high, one roof triangle
// a cap (its corner c 0.01 from the ridge's line), the two side triangles
// at c bent outward: a vertex on the ear's interior edge (c, d) leaves a
// thin tet on the cap, and the relaxation of its new nodes, spread from the
// bent sides, turns it inside out (as on nefertiti's cap triangle,
// docs/usable_elements.md).
mesh::TetMesh roof_with_an_ear_on_a_cap() {
  const int a = 0, b = 1, c = 2, d = 3, e = 4;
  const auto linear = linear_mesh({Vec3(-1, 0, 0.003), Vec3(1, 0, 0.003), Vec3(0.3, -0.01, 0), Vec3(0, 1, 0),
                                   Vec3(0, 0, -1.2)},
                                  {{a, b, c, d}, {a, c, d, e}, {b, c, d, e}}, {});
  std::vector<std::array<int, 4>> tets(linear.num_tets());
  for (int t = 0; t < linear.num_tets(); ++t) std::copy(linear.tet(t), linear.tet(t) + 4, tets[t].begin());
  auto m = test::straight_mesh(linear.nodes, tets, 4);
  // The side triangles at c (those with corners c and e): every node off
  // the roof's edges pushed outward (-y), most at mid-height.
  for (int f = 0; f < m.num_boundary(); ++f) {
    const int* t = m.boundary_triangle(f);
    const int* e_at = std::find(t, t + 3, e);
    if (e_at == t + 3 || std::find(t, t + 3, c) == t + 3) continue;
    for (int i = 3; i < m.triangle_nodes(); ++i) {
      const auto q = highorder::triangle_node(4, i);
      const std::array<int, 3> w = {4 - q[0] - q[1], q[0], q[1]};
      const double on_e = w[e_at - t] / 4.0;
      m.nodes[t[i]].y() -= 0.4 * on_e * (1 - on_e);
    }
  }
  return m;
}

TEST(CurvedRemesh, SplitsAnEarOnACapTriangleWithStraightNewNodes) {
  auto m = roof_with_an_ear_on_a_cap();
  ASSERT_TRUE(check::verify_tet_mesh(m).ok()) << check::verify_tet_mesh(m).text();
  volume::CurvedRemeshOptions o;
  o.flip = o.smooth = o.descend = false; // the splits alone (every vertex is frozen: no collapse)
  const auto s = volume::remesh_curved(m, o);
  EXPECT_GT(s.max_amips_before, 130);
  EXPECT_GE(s.splits, 1); // none when the split is previewed relaxed only
  EXPECT_LT(s.max_amips_after, 0.9 * s.max_amips_before);
  const auto v = check::verify_tet_mesh(m);
  EXPECT_TRUE(v.ok()) << v.text();
}

// A bipyramid over an equilateral triangle, filled by the three tets
// around its axis: every vertex is on the boundary, and the 3-2 flip of
// the axis gives two good tets, one fewer.
mesh::TetMesh bipyramid_around_its_axis() {
  const double s = std::sqrt(3.0) / 2;
  const int a = 0, b = 1;
  // Outward: the upper faces counter-clockwise seen from above, the lower ones from below.
  return linear_mesh({Vec3(0, 0, -0.8), Vec3(0, 0, 0.8), Vec3(1, 0, 0), Vec3(-0.5, s, 0), Vec3(-0.5, -s, 0)},
                     {{a, b, 2, 3}, {a, b, 3, 4}, {a, b, 4, 2}},
                     {b, 2, 3, b, 3, 4, b, 4, 2, a, 3, 2, a, 4, 3, a, 2, 4});
}

TEST(CurvedRemesh, ThreeTwoFlipsLowerTheTetCount) {
  volume::CurvedRemeshOptions o;
  o.smooth = o.descend = false;
  auto m = bipyramid_around_its_axis();
  ASSERT_TRUE(check::verify_tet_mesh(m).ok()) << check::verify_tet_mesh(m).text();
  const auto s = volume::remesh_curved(m, o);
  EXPECT_LT(s.max_amips_before, o.target_amips); // not a quality visit: the coarsening's flip
  EXPECT_EQ(s.flips_3_2, 1);
  EXPECT_EQ(m.num_tets(), 2);
  EXPECT_LE(s.max_amips_after, o.target_amips);
  const auto v = check::verify_tet_mesh(m);
  EXPECT_TRUE(v.ok()) << v.text();
}

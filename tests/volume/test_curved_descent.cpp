// Joint descent: lowers the worst tet, moves no boundary node, keeps every
// tet certified positive, and is deterministic.
#include "curvetet/check/verify_tet_mesh.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/volume/curved_descent.hpp"
#include "curvetet/volume/curved_optimize.hpp"
#include "flat_inner_tet.hpp"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

using namespace curvetet;

TEST(CurvedDescent, LowersTheWorstTetAndKeepsTheBoundaryAndPositivity) {
  for (int order : {2, 3, 4}) {
    SCOPED_TRACE(order);
    auto m = test::flat_inner_tet_mesh(order);
    const auto before_check = check::verify_tet_mesh(m);
    ASSERT_TRUE(before_check.ok());
    const auto before = m;
    const auto stats = volume::descend_curved(m);
    EXPECT_GT(stats.free_nodes, 0);
    EXPECT_GT(stats.iterations, 0);
    EXPECT_LT(stats.energy_after, stats.energy_before);
    for (int id : m.boundary) EXPECT_EQ(m.nodes[id], before.nodes[id]) << "node " << id;
    EXPECT_EQ(m.tets, before.tets);
    const auto v = check::verify_tet_mesh(m);
    ASSERT_TRUE(v.ok()) << v.text();
    EXPECT_LT(v.worst_amips, 0.8 * before_check.worst_amips) << before_check.worst_amips << " -> " << v.worst_amips;
    EXPECT_GE(v.worst_scaled_jacobian, before_check.worst_scaled_jacobian);
  }
}

TEST(CurvedDescent, NothingMovesWhenEveryNodeIsOnTheHull) {
  // One order-3 tet, unlisted: every node lies on a face used once.
  mesh::TetMesh m;
  m.order = 3;
  for (int i = 0; i < m.tet_nodes(); ++i) {
    const auto q = highorder::tet_node(3, i);
    m.nodes.push_back(mesh::Vec3(q[0] + 2.0 * q[1], 0.3 * q[1], 0.1 * q[2]) / 3.0);
    m.tets.push_back(i);
  }
  const auto before = m.nodes;
  const auto stats = volume::descend_curved(m);
  EXPECT_EQ(stats.free_nodes, 0);
  EXPECT_EQ(m.nodes, before);
}

TEST(CurvedDescent, ThreadCountDoesNotChangeTheResult) {
  auto a = test::flat_inner_tet_mesh(4), b = a;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    volume::descend_curved(a);
  }
  {
    tbb::global_control four(tbb::global_control::max_allowed_parallelism, 4);
    volume::descend_curved(b);
  }
  EXPECT_EQ(a.nodes, b.nodes);
}

TEST(CurvedDescent, OnlyTheWorstTetsAndTheirRingsMove) {
  auto all = test::flat_inner_tet_mesh(4), worst = all;
  volume::CurvedDescentOptions o;
  o.active_ratio = 0; // every tet
  const auto every = volume::descend_curved(all, o);
  o.active_ratio = 1; // the worst tet alone
  o.rings = 0;
  const auto before = worst;
  const auto one = volume::descend_curved(worst, o);
  EXPECT_GT(one.free_nodes, 0);
  EXPECT_LT(one.free_nodes, every.free_nodes);
  // Only free nodes move.
  const auto q = check::verify_tet_mesh(before);
  int moved = 0;
  for (std::size_t n = 0; n < worst.nodes.size(); ++n) moved += worst.nodes[n] != before.nodes[n];
  EXPECT_GT(moved, 0);
  EXPECT_LE(moved, one.free_nodes);
  const auto v = check::verify_tet_mesh(worst);
  ASSERT_TRUE(v.ok()) << v.text();
  EXPECT_LT(v.worst_amips, q.worst_amips);
}

TEST(CurvedDescent, LongerRunsAreNeverWorseAtTheirWorst) {
  // The worst falls in bursts: a run allowed more iterations ends at least
  // as good as a short one (the long run checks its best iterate every
  // checkpoint_iterations and keeps the last that passed), and certified.
  auto shorter = test::flat_inner_tet_mesh(4), longer = shorter;
  volume::CurvedDescentOptions o;
  o.max_iterations = 20;
  volume::descend_curved(shorter, o);
  o.max_iterations = 1000;
  o.checkpoint_iterations = 20;
  const auto stats = volume::descend_curved(longer, o);
  EXPECT_GT(stats.iterations, 20);
  const auto s = check::verify_tet_mesh(shorter), l = check::verify_tet_mesh(longer);
  ASSERT_TRUE(l.ok()) << l.text();
  EXPECT_LE(l.worst_amips, s.worst_amips);
  EXPECT_GE(l.worst_scaled_jacobian, s.worst_scaled_jacobian);
}

// The per-tet quality handed in is taken as the input's and given back as
// the result's: the same figures as measuring the result afresh, and the
// same result as without it.
TEST(CurvedDescent, HandedQualityComesBackAsTheResults) {
  for (int order : {2, 4}) {
    SCOPED_TRACE(order);
    auto m = test::flat_inner_tet_mesh(order);
    auto plain = m;
    const std::vector<highorder::TetQuality> initial = volume::tet_qualities(m);
    std::vector<highorder::TetQuality> quality = initial;
    volume::descend_curved(m, {}, &quality);
    volume::descend_curved(plain);
    EXPECT_EQ(m.nodes, plain.nodes);
    const auto fresh = volume::tet_qualities(m);
    ASSERT_EQ(quality.size(), fresh.size());
    bool some_moved = false;
    for (std::size_t t = 0; t < fresh.size(); ++t) {
      EXPECT_EQ(quality[t].max_amips, fresh[t].max_amips) << "tet " << t;
      EXPECT_EQ(quality[t].mean_amips, fresh[t].mean_amips) << "tet " << t;
      EXPECT_EQ(quality[t].min_scaled_jacobian, fresh[t].min_scaled_jacobian) << "tet " << t;
      some_moved = some_moved || fresh[t].max_amips != initial[t].max_amips;
    }
    EXPECT_TRUE(some_moved);
  }
}

// The combinatorial core the volume stage's editors share: stars stay in
// the order the schedulers rely on through kill, add, revive and renames.
#include "curvetet/volume/edit/tet_stars.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

using curvetet::volume::edit::Corners;
using curvetet::volume::edit::TetStars;

namespace {

// Four tets around edge (0, 1), its ring 2-3-4-5 closed.
TetStars closed_ring() {
  return TetStars({{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 5}, {0, 1, 5, 2}}, 6);
}

} // namespace

TEST(TetStars, StarsFollowKillsAddsAndRevivals) {
  auto m = closed_ring();
  EXPECT_EQ(m.star(3), (std::vector<int>{0, 1}));
  m.kill(0);
  EXPECT_FALSE(m.alive(0));
  EXPECT_EQ(m.star(0), (std::vector<int>{1, 2, 3})); // the others keep their order
  EXPECT_EQ(m.star(3), (std::vector<int>{1}));
  const int t = m.add({2, 3, 4, 0});
  EXPECT_EQ(t, 4);
  EXPECT_EQ(m.star(3), (std::vector<int>{1, 4})); // appended
  m.revive(0);
  EXPECT_EQ(m.star(3), (std::vector<int>{1, 4, 0}));
  EXPECT_THROW(m.revive(0), std::logic_error);
  m.kill(0);
  EXPECT_THROW(m.kill(0), std::logic_error);
  m.pop_slot();
  EXPECT_EQ(m.num_slots(), 4);
  EXPECT_EQ(m.star(3), (std::vector<int>{1}));
}

TEST(TetStars, AddingOneOfItsOwnCornersIsSafe) {
  auto m = closed_ring();
  for (int i = 0; i < 64; ++i) m.add(m.corners(0)); // push_back may reallocate while reading
  EXPECT_EQ(m.corners(64), (Corners{0, 1, 2, 3}));
  EXPECT_EQ(m.star(2).size(), 2u + 64u);
  EXPECT_EQ(m.star(2).back(), 67);
}

TEST(TetStars, EdgeRingAndItsCycle) {
  const auto m = closed_ring();
  const auto ring = m.edge_ring(0, 1);
  EXPECT_EQ(ring, (std::vector<int>{0, 1, 2, 3}));
  const auto cycle = m.ring_cycle(0, 1, ring);
  ASSERT_EQ(cycle.size(), 4u);
  for (int i = 0; i < 4; ++i) // consecutive ring vertices share a tet with the edge
    EXPECT_TRUE(m.has_face(0, cycle[i], cycle[(i + 1) % 4])) << i;
  EXPECT_TRUE(m.has_edge(2, 3));
  EXPECT_FALSE(m.has_edge(2, 4)); // a diagonal of the ring
  EXPECT_FALSE(m.has_face(0, 2, 4));
  EXPECT_EQ(m.neighbours(2), (std::vector<int>{0, 1, 3, 5}));
  // Open fan: the edge (0, 2) has two tets, no closed ring.
  EXPECT_TRUE(m.ring_cycle(0, 2, m.edge_ring(0, 2)).empty());
}

TEST(TetStars, RenamingACornerMovesTheTetBetweenStars) {
  // Collapsing 3 onto 2: the tet on edge (2, 3) goes, the other takes 2.
  auto n = TetStars({{0, 1, 2, 3}, {0, 1, 3, 4}}, 6);
  n.kill(0);
  n.rename_corner(1, 3, 2);
  EXPECT_EQ(n.corners(1), (Corners{0, 1, 2, 4}));
  EXPECT_TRUE(n.star(3).empty());
  EXPECT_EQ(n.star(2), (std::vector<int>{1}));
  n.add_vertex();
  EXPECT_EQ(n.num_vertices(), 7);
  n.pop_vertex();
  EXPECT_THROW(TetStars({{0, 1, 2, 3}}, 4).pop_vertex(), std::logic_error); // vertex 3 has a tet
}

// lk(0) ∩ lk(1) holds vertex 4 (tets 0-4 and 1-4 exist) but lk(01) is the
// edge 2-3 only: collapsing 1 onto 0 would make two tets share edge 0-4 in
// a way the mesh cannot hold. Without the tet (0, 4, 5, 6) (outside the
// region asked for) the condition holds.
TEST(TetStars, LinkConditionSeesACommonNeighbourOffTheEdge) {
  const TetStars m({{0, 1, 2, 3}, {0, 4, 5, 6}, {1, 4, 7, 8}}, 9);
  TetStars::LinkBuffers buffers;
  EXPECT_FALSE(m.link_condition(0, 1, buffers));
  EXPECT_TRUE(m.link_condition(0, 1, buffers, [](int t) { return t != 1; }));
  const TetStars single({{0, 1, 2, 3}}, 4);
  EXPECT_TRUE(single.link_condition(0, 3, buffers)); // one tet: lk(03) = edge 1-2
  const TetStars pair({{0, 1, 2, 3}, {1, 0, 2, 4}}, 5); // two tets on face 0-1-2
  EXPECT_FALSE(pair.link_condition(3, 4, buffers)); // not an edge: lk(3) and lk(4) share triangle 0-1-2
}

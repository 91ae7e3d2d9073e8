// Node placement of curved slab tets (shared by the assembly and the
// shell's certificate): on the slab map in general, on the curved patch on
// the middle surface, on the straight tet beside a pinched pillar.
#include "curvetet/highorder/conforming_nodes.hpp"
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/jacobian_certificate.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/shell/slab_tet_nodes.hpp"

#include <gtest/gtest.h>

using namespace curvetet;
using namespace curvetet::shell;

namespace {

// A quadratic middle patch over the unit right triangle at height 1, bulged
// up by b at the edge midpoints; bottom cap at height 0.
struct Slab {
  std::vector<Vec3> middle;
  SlabPatch patch;
  explicit Slab(double b, std::array<bool, 3> pinched) {
    const int k = 2;
    middle.resize(highorder::triangle_node_count(k));
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        const double u = double(i) / k, v = double(j) / k;
        const bool corner = (i == 0 || i == k) && (j == 0 || j == k);
        middle[highorder::triangle_node_index(k, {i, j})] = Vec3(u, v, 1 + (corner ? 0 : b));
      }
    patch.degree = k;
    patch.middle_nodes = middle.data();
    patch.bottom = true;
    patch.pinched = pinched;
    for (int c = 0; c < 3; ++c) {
      patch.cap[c] = middle[c];
      if (!pinched[c]) patch.cap[c].z() = 0;
    }
  }
};

} // namespace

TEST(SlabTetNodes, FollowTheSlabMapAndThePatch) {
  Slab s(0.1, {false, false, false});
  const int order = 3;
  for (const auto& tet : canonical_split({0, 1, 2})) {
    const auto nodes = slab_tet_nodes(s.patch, tet, order);
    ASSERT_EQ(static_cast<int>(nodes.size()), highorder::tet_node_count(order));
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
      const auto l = highorder::tet_node_barycentric(order, i);
      std::array<double, 3> uvw{0, 0, 0};
      for (int j = 0; j < 4; ++j)
        for (int d = 0; d < 3; ++d) uvw[d] += l[j] * reference_corner(tet.corners[j])[d];
      const Vec3 m = highorder::triangle_point(2, s.middle.data(), Eigen::Vector2d(uvw[0], uvw[1]));
      const Vec3 flat(uvw[0], uvw[1], 0);
      EXPECT_LT((nodes[i] - ((1 - uvw[2]) * flat + uvw[2] * m)).norm(), 1e-14);
    }
    EXPECT_EQ(highorder::certify_tet(order, nodes.data()).validity, highorder::Validity::positive);
  }
}

TEST(SlabTetNodes, StraightBesideAPinchedPillarExceptOnTheMiddle) {
  Slab s(0.1, {true, false, false});
  const int order = 3;
  int straight = 0, on_patch = 0;
  for (const auto& tet : canonical_split({0, 1, 2})) {
    if (tet.pillar == 0) continue; // degenerate: not in the output
    const auto nodes = slab_tet_nodes(s.patch, tet, order);
    std::array<Vec3, 4> corner;
    std::array<bool, 4> pinched{}, upper{};
    for (int j = 0; j < 4; ++j) {
      const int c = tet.corners[j];
      pinched[j] = c % 3 == 0;
      upper[j] = c >= 3 || pinched[j];
      corner[j] = upper[j] ? s.middle[c % 3] : s.patch.cap[c % 3];
    }
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
      const auto l = highorder::tet_node_barycentric(order, i);
      bool near_pinch = false, middle = true;
      Vec3 linear = Vec3::Zero();
      for (int j = 0; j < 4; ++j) {
        linear += l[j] * corner[j];
        if (l[j] > 0) near_pinch |= pinched[j], middle &= upper[j];
      }
      if (near_pinch && !middle) {
        EXPECT_LT((nodes[i] - linear).norm(), 1e-15);
        ++straight;
      } else if (middle) {
        // On the middle surface: on the curved patch (z above the plane).
        EXPECT_GE(nodes[i].z(), 1.0 - 1e-15);
        ++on_patch;
      }
    }
  }
  EXPECT_GT(straight, 0);
  EXPECT_GT(on_patch, 0);
}

namespace {

// The straight tet's point at node i of `tet` (corners: middle corners on
// the upper side of a bottom slab, cap corners below).
Vec3 linear_node(const Slab& s, const SlabTet& tet, int order, int i, bool* on_middle, std::array<bool, 3>* pillars) {
  const auto l = highorder::tet_node_barycentric(order, i);
  Vec3 x = Vec3::Zero();
  *on_middle = true;
  *pillars = {false, false, false};
  for (int j = 0; j < 4; ++j) {
    const int c = tet.corners[j];
    x += l[j] * (c >= 3 ? s.middle[c % 3] : s.patch.cap[c % 3]);
    if (l[j] > 0) *on_middle &= c >= 3, (*pillars)[c % 3] = true;
  }
  return x;
}

} // namespace

// With straight parts on (Shell::straight_slab_parts): a flat patch over a
// twisted prism (non-planar lateral quads) gives the straight tets, the ones
// invariant 1 proves positive, not the bilinear slab map.
TEST(SlabTetNodes, FlatPatchGivesTheStraightTets) {
  Slab s(0.0, {false, false, false});
  s.patch.straight_parts = true;
  s.patch.cap[1] += Vec3(0.3, 0.4, 0.2); // twists the quads over edges (0, 1) and (1, 2)
  const int order = 3;
  EXPECT_TRUE(straight_parts(s.patch).whole);
  for (const auto& tet : canonical_split({0, 1, 2})) {
    const auto nodes = slab_tet_nodes(s.patch, tet, order);
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
      bool on_middle;
      std::array<bool, 3> pillars;
      EXPECT_LT((nodes[i] - linear_node(s, tet, order, i, &on_middle, &pillars)).norm(), 1e-15) << i;
    }
  }
}

// A patch curved except along edge (0, 1): off the middle, nodes over that
// edge's lateral quad are on the straight tet (as a flat neighbour across the
// edge places them), nodes spanning all three pillars on the slab map.
TEST(SlabTetNodes, StraightOnlyOverTheStraightEdge) {
  Slab s(0.1, {false, false, false});
  s.middle[highorder::triangle_node_index(2, {1, 0})].z() = 1; // the midpoint of edge (0, 1) back on the chord
  s.patch.straight_parts = true;
  s.patch.cap[1] += Vec3(0.3, 0.4, 0.2);
  const auto parts = straight_parts(s.patch);
  EXPECT_TRUE(parts.edge[2]); // edge (0, 1) is opposite corner 2
  EXPECT_FALSE(parts.edge[0] || parts.edge[1] || parts.whole);
  const int order = 3;
  int over_edge = 0, inside = 0;
  for (const auto& tet : canonical_split({0, 1, 2})) {
    const auto nodes = slab_tet_nodes(s.patch, tet, order);
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
      bool on_middle;
      std::array<bool, 3> pillars;
      const Vec3 linear = linear_node(s, tet, order, i, &on_middle, &pillars);
      if (on_middle) continue;
      const int spans = pillars[0] + pillars[1] + pillars[2];
      if (spans == 2 && !pillars[2]) {
        EXPECT_LT((nodes[i] - linear).norm(), 1e-15);
        ++over_edge;
      } else if (spans == 3 && (nodes[i] - linear).norm() > 1e-3) {
        ++inside; // on the curved slab map
      }
    }
  }
  EXPECT_GT(over_edge, 0);
  EXPECT_GT(inside, 0);
}

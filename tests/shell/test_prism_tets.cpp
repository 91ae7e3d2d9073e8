// The slab tet tables and the orientation convention of the shell.
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/shell/prism_tets.hpp"

#include <gtest/gtest.h>

#include <set>

using namespace curvetet::shell;
using curvetet::geometry::orient3d;
using V = Eigen::Vector3d;

namespace {
// Right prism over the counter-clockwise unit triangle, upper = lower + z.
V corner_of(int c) {
  auto r = reference_corner(c);
  return V(r[0], r[1], r[2]);
}
double volume(const SlabTet& t) {
  V p[4];
  for (int i = 0; i < 4; ++i) p[i] = corner_of(t.corners[i]);
  return (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6;
}
} // namespace

TEST(SlabTets, TwelveDistinctTetsEachWithOnePillarAllPositiveOnRightPrism) {
  std::set<std::set<int>> seen;
  for (const auto& t : all_slab_tets()) {
    std::set<int> s(t.corners.begin(), t.corners.end());
    EXPECT_EQ(s.size(), 4u);
    seen.insert(s);
    EXPECT_TRUE(s.count(t.pillar) && s.count(t.pillar + 3));
    EXPECT_EQ(orient3d(corner_of(t.corners[0]), corner_of(t.corners[1]), corner_of(t.corners[2]),
                       corner_of(t.corners[3])),
              1);
  }
  EXPECT_EQ(seen.size(), 12u);
}

TEST(SlabTets, CanonicalSplitTilesThePrismAndAgreesOnSharedQuads) {
  // Every ordering of ids gives 3 positive tets of volume 1/2 in total, one
  // per pillar.
  for (auto ids : std::vector<std::array<int, 3>>{{0, 1, 2}, {2, 0, 1}, {7, 3, 5}, {1, 9, 4}, {5, 4, 3}, {3, 8, 9}}) {
    const auto split = canonical_split(ids);
    double total = 0;
    std::set<int> pillars;
    for (const auto& t : split) {
      EXPECT_GT(volume(t), 0);
      total += volume(t);
      pillars.insert(t.pillar);
    }
    EXPECT_NEAR(total, 0.5, 1e-15);
    EXPECT_EQ(pillars.size(), 3u);
    // The quad over edge (i, j) is cut from lower[min id] to upper[max id]:
    // that diagonal is an edge of some tet; the other one is not.
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      const int lo = ids[i] < ids[j] ? i : j, hi = lo == i ? j : i;
      bool has_diag = false, has_other = false;
      for (const auto& t : split) {
        std::set<int> s(t.corners.begin(), t.corners.end());
        has_diag |= s.count(lo) && s.count(hi + 3);
        has_other |= s.count(hi) && s.count(lo + 3);
      }
      EXPECT_TRUE(has_diag);
      EXPECT_FALSE(has_other);
    }
  }
}

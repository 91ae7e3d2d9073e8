// The Section rule's contact test: a triangle may touch a slab tet at an
// allowed corner or along an allowed edge, never inside it or elsewhere.
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/shell/tet_contact.hpp"

#include <gtest/gtest.h>

#include <array>

using namespace curvetet;
using namespace curvetet::shell;

namespace {

struct Case {
  std::array<Vec3, 4> tet{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  std::array<Vec3, 3> tri;

  bool meets_outside(std::array<bool, 4> allowed) {
    if (geometry::orient3d(tet[0], tet[1], tet[2], tet[3]) < 0) std::swap(tet[2], tet[3]);
    const Vec3* t[4] = {&tet[0], &tet[1], &tet[2], &tet[3]};
    const Vec3* f[3] = {&tri[0], &tri[1], &tri[2]};
    return triangle_meets_tet_outside(f, t, allowed.data());
  }
};

} // namespace

TEST(TetContact, TouchAtAnAllowedCornerIsExempt) {
  // In the plane x = 0, in the quadrant opposite the tet's face.
  Case c{.tri = {Vec3(0, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1)}};
  EXPECT_FALSE(c.meets_outside({true, false, false, false}));
  EXPECT_TRUE(c.meets_outside({false, true, false, false}));
  EXPECT_TRUE(c.meets_outside({false, false, false, false}));
}

TEST(TetContact, EnteringThroughAnAllowedCornerIsNot) {
  Case c{.tri = {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 0, -1)}};
  EXPECT_TRUE(c.meets_outside({true, false, false, false}));
  EXPECT_TRUE(c.meets_outside({true, true, true, true}));
}

TEST(TetContact, PlaneCuttingTheTetButTriangleTurningAwayIsExempt) {
  // The triangle's plane -x - y + z = 0 cuts the tet; the triangle itself
  // has x < 0 except at the corner: separated by the tet's face x = 0.
  Case c{.tri = {Vec3(0, 0, 0), Vec3(-1, 1, 0), Vec3(-1, 0, -1)}};
  EXPECT_FALSE(c.meets_outside({true, false, false, false}));
  EXPECT_TRUE(c.meets_outside({false, false, true, false}));
}

TEST(TetContact, TouchAlongAnAllowedEdgeIsExempt) {
  // Plane x + y - z = 1 holds the edge (1,0,0)-(0,1,0); the tet's other two
  // corners lie strictly below it.
  Case c{.tri = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 1)}};
  EXPECT_FALSE(c.meets_outside({false, true, true, false}));
  EXPECT_TRUE(c.meets_outside({false, true, false, false})); // the edge is more than the corner
  EXPECT_TRUE(c.meets_outside({true, false, false, true}));
}

TEST(TetContact, PartOfAnAllowedEdgeIsExemptButCrossingItIsNot) {
  Case touching{.tri = {Vec3(0.25, 0.75, 0), Vec3(0.75, 0.25, 0), Vec3(1, 1, 1)}};
  EXPECT_FALSE(touching.meets_outside({false, true, true, false}));
  // Same edge points, third corner on the tet's side: the triangle enters.
  Case entering{.tri = {Vec3(0.25, 0.75, 0), Vec3(0.75, 0.25, 0), Vec3(0.1, 0.1, 0.1)}};
  EXPECT_TRUE(entering.meets_outside({false, true, true, false}));
}

TEST(TetContact, NoContactIsNoContact) {
  Case c{.tri = {Vec3(2, 2, 2), Vec3(3, 2, 2), Vec3(2, 3, 2)}};
  EXPECT_FALSE(c.meets_outside({false, false, false, false}));
  const Vec3* t[4] = {&c.tet[0], &c.tet[1], &c.tet[2], &c.tet[3]};
  const Vec3* f[3] = {&c.tri[0], &c.tri[1], &c.tri[2]};
  EXPECT_FALSE(triangle_meets_tet(f, t));
}

TEST(TetContact, AllowedCornersAreTheOtherPillarsMiddleEnds) {
  // Bottom slab: the middle is the upper side (corners 3..5).
  const SlabTet t{{0, 3, 4, 5}, 0};
  const auto bottom = section_allowed_corners(t, true);
  EXPECT_EQ(bottom, (std::array<bool, 4>{false, false, true, true}));
  const SlabTet u{{0, 1, 2, 4}, 1};
  const auto top = section_allowed_corners(u, false);
  EXPECT_EQ(top, (std::array<bool, 4>{true, false, true, false}));
}

// The quick separation (boxes, then the tet's face planes) must keep the
// test closed: a triangle beside the slanted face with overlapping boxes
// does not meet the tet, one lying in that face's plane across it does.
TEST(TetContact, FacePlaneSeparationKeepsTheTestClosed) {
  Case c;
  const Vec3* t[4] = {&c.tet[0], &c.tet[1], &c.tet[2], &c.tet[3]};
  const Vec3* f[3] = {&c.tri[0], &c.tri[1], &c.tri[2]};
  c.tri = {Vec3(0.6, 0.6, 0.1), Vec3(0.1, 0.6, 0.6), Vec3(0.6, 0.1, 0.6)}; // x + y + z = 1.3 > 1
  EXPECT_FALSE(triangle_meets_tet(f, t));
  c.tri = {Vec3(0.5, 0.5, 0), Vec3(0, 0.5, 0.5), Vec3(0.5, 0, 0.5)}; // on x + y + z = 1, inside the face
  EXPECT_TRUE(triangle_meets_tet(f, t));
  c.tri = {Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(2, 0, 1)}; // touches one corner only
  EXPECT_TRUE(triangle_meets_tet(f, t));
}

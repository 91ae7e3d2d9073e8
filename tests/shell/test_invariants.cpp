// One test per shell invariant: a tiny configuration rejected, one accepted.
#include "curvetet/shell/invariant_set.hpp"
#include "curvetet/shell/invariants.hpp"

#include <gtest/gtest.h>

using namespace curvetet;
using namespace curvetet::shell;

namespace {

// One prism over the counter-clockwise triangle m0 m1 m2 in the plane z = 0
// (normal +z), pillars of half-length 1 (straight up and down):
//
//      t2                      t_i = m_i + (0,0,1)
//     /|\ t1      top  T       m_i = corners below
//   t0-+-/                     b_i = m_i - (0,0,1)
//      m2
//     / \  m1     middle V = input face (tracked)
//   m0---/
//      b2
//     / \  b1     bottom B
//   b0---/
Shell one_prism() {
  Shell s;
  s.middle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.faces = {{0, 1, 2}};
  for (const auto& m : s.middle) {
    s.top.push_back(m + Vec3(0, 0, 1));
    s.bottom.push_back(m - Vec3(0, 0, 1));
  }
  s.input.vertices = s.middle;
  s.input.faces = s.faces;
  s.tracked = {{0}};
  s.singular = {0, 0, 0};
  return s;
}

} // namespace

TEST(PrismPositivity, RightPrismAccepted) {
  EXPECT_TRUE(prism_positive(one_prism(), 0));
  EXPECT_TRUE(non_positive_prisms(one_prism()).empty());
}

TEST(PrismPositivity, TwistedTopRejected) {
  // Rotating the top triangle by ~80 degrees about its centroid inverts some
  // of the 12 tets (the check must look at all of them).
  Shell s = one_prism();
  const Vec3 c(1.0 / 3, 1.0 / 3, 1);
  const double a = 1.4;
  for (auto& t : s.top) {
    const Vec3 d = t - c;
    t = c + Vec3(std::cos(a) * d[0] - std::sin(a) * d[1], std::sin(a) * d[0] + std::cos(a) * d[1], 0);
  }
  EXPECT_FALSE(prism_positive(s, 0));
}

TEST(PrismPositivity, FlatSlabRejected) {
  // Top vertex 2 lowered onto the middle plane (not pinched: it moved
  // sideways): the tets on pillar 2 are flat, orient3d = 0 is not positive.
  Shell s = one_prism();
  s.top[2] = Vec3(0.2, 0.9, 0);
  EXPECT_FALSE(prism_positive(s, 0));
}

TEST(PrismPositivity, PinchedPillarGivesAPyramidThatIsAccepted) {
  // Vertex 0 singular: b0 = m0 = t0. Degenerate tets skipped, others positive.
  Shell s = one_prism();
  s.top[0] = s.bottom[0] = s.middle[0];
  EXPECT_TRUE(prism_positive(s, 0));
  // ... but a pinched prism whose other pillar points down is still rejected.
  s.top[1] = s.middle[1] - Vec3(0, 0, 0.5);
  EXPECT_FALSE(prism_positive(s, 0));
}

TEST(Section, MiddleFaceAccepted) { EXPECT_TRUE(invalid_section_prisms(one_prism()).empty()); }

TEST(Section, SlightlyTiltedInputFaceInsideAccepted) {
  // Tracked face inside the prism, normal still within 90 deg of the pillars.
  Shell s = one_prism();
  s.input.vertices = {{0.1, 0.1, -0.2}, {0.8, 0.1, 0.3}, {0.1, 0.8, 0.1}};
  EXPECT_TRUE(invalid_section_prisms(s).empty());
}

TEST(Section, SteepInputFaceRejected) {
  // A vertical tracked face (normal -y, orthogonal to the pillars) and one
  // leaning past vertical (normal . pillar < 0), both inside the prism.
  //     side view (x, z):   | z
  //                 t       |/  <- tracked face, nearly vertical
  //                 m  ----/----
  Shell s = one_prism();
  s.input.vertices = {{0.1, 0.1, -0.5}, {0.6, 0.1, -0.5}, {0.1, 0.1, 0.5}};
  EXPECT_FALSE(invalid_section_prisms(s).empty());
  s.input.vertices = {{0.1, 0.1, -0.5}, {0.6, 0.1, -0.5}, {0.1, 0.05, 0.5}};
  EXPECT_FALSE(invalid_section_prisms(s).empty());
}

TEST(Section, InputFaceLeavingThePrismRejected) {
  // Tracked face sticks out of the prism through the top cap.
  Shell s = one_prism();
  s.input.vertices = {{0.1, 0.1, 0}, {0.8, 0.1, 0}, {0.1, 0.8, 1.5}};
  EXPECT_FALSE(invalid_section_prisms(s).empty());
}

TEST(CapsIntersectionFree, TwoStackedPrisms) {
  // Two separate prisms over the same triangle shape, one 1 unit above the
  // other, pillar half-length 0.3: caps apart -> accepted. Lengthen the
  // upper prism's bottom pillars to 0.8: its bottom cap passes below the
  // lower prism's top cap, and they cross (the upper one is tilted) ->
  // rejected.
  //
  //  z=1.3 ______ T1
  //  z=1.0 ______ V1          z=1.0 ______ V1
  //  z=0.7 ______ B1                   /
  //  z=0.3 ______ T0   -->    z=0.3 __/___ T0   (B1 tilted through T0)
  //  z=0   ______ V0          z=0   ______ V0
  Shell s;
  s.middle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  s.faces = {{0, 1, 2}, {3, 4, 5}};
  for (const auto& m : s.middle) {
    s.top.push_back(m + Vec3(0, 0, 0.3));
    s.bottom.push_back(m - Vec3(0, 0, 0.3));
  }
  s.input.vertices = s.middle;
  s.input.faces = s.faces;
  s.tracked = {{0}, {1}};
  s.singular.assign(6, 0);
  EXPECT_TRUE(cap_intersections(s).empty());
  EXPECT_TRUE(check_shell(s).empty());
  s.bottom[3] = s.middle[3] - Vec3(0, 0, 0.9);
  s.bottom[4] = s.middle[4] - Vec3(0, 0, 0.5);
  s.bottom[5] = s.middle[5] - Vec3(0, 0, 0.5);
  const auto hits = cap_intersections(s);
  ASSERT_EQ(hits.size(), 1u);
  // Cap ids: bottom f = f, top f = F + f: top of prism 0 is 2, bottom of 1 is 1.
  EXPECT_EQ(hits[0], std::make_pair(1, 2));
  // The local check from prism 1 alone finds it too; from prism 0 as well.
  EXPECT_EQ(cap_intersections(s, std::vector<int>{1}).size(), 1u);
  EXPECT_EQ(cap_intersections(s, std::vector<int>{0}).size(), 1u);
}

TEST(CapsIntersectionFree, SharedPinchedVertexIsNotAnIntersection) {
  // A singular vertex is shared by the bottom and top caps around it.
  Shell s;
  s.middle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.faces = {{0, 1, 2}};
  s.top = {{0, 0, 0}, {1, 0, 0.2}, {0, 1, 0.2}};
  s.bottom = {{0, 0, 0}, {1, 0, -0.2}, {0, 1, -0.2}};
  s.input.vertices = s.middle;
  s.input.faces = s.faces;
  s.tracked = {{0}};
  s.singular = {1, 0, 0};
  EXPECT_TRUE(check_shell(s).empty());
  // Moving the bottom cap's corner 1 above the top cap makes them cross.
  s.bottom[1] = Vec3(1, 0, 0.4);
  EXPECT_FALSE(cap_intersections(s).empty());
}

TEST(InvariantSet, NamesTheFirstFailingInvariant) {
  const auto set = InvariantSet::shell_invariants();
  const std::vector<int> prism0{0};
  Shell ok = one_prism();
  EXPECT_FALSE(set.first_failure(ok, prism0, {}).has_value());
  Shell flat = one_prism();
  flat.top[2] = Vec3(0.2, 0.9, 0);
  EXPECT_EQ(set.first_failure(flat, prism0, {}), InvariantKind::prism_positivity);
  Shell steep = one_prism();
  steep.input.vertices = {{0.1, 0.1, -0.5}, {0.6, 0.1, -0.5}, {0.1, 0.1, 0.5}};
  EXPECT_EQ(set.first_failure(steep, prism0, {}), InvariantKind::section);
}

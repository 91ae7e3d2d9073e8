// One rejection test per invariant of the coarsening invariant list, on
// shells built by hand (one or two prisms), plus the accepted identity.
//
//   one prism over the right triangle 0 (0,0) - 1 (1,0) - 2 (0,1):
//   middle at z = 0, bottom at z = -1, top at z = +1, vertical pillars.
//
//        2
//        | \          seen from the top (+z): counter-clockwise
//        |   \ .
//        0 --- 1
#include "curvetet/shell/shell_editor.hpp"
#include "curvetet/shell/star_invariants.hpp"

#include <gtest/gtest.h>

#include <limits>

using namespace curvetet;
using namespace curvetet::shell;

namespace {

// `input` are the input triangle's corners (counter-clockwise = normal +z).
Shell one_prism(std::array<Vec3, 3> input, double z0 = 0) {
  Shell s;
  const Vec3 base[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (int k = 0; k < 3; ++k) {
    const Vec3 up(0, 0, 1);
    s.middle.push_back(base[k] + z0 * up);
    s.bottom.push_back(base[k] + (z0 - 1) * up);
    s.top.push_back(base[k] + (z0 + 1) * up);
  }
  s.faces = {{0, 1, 2}};
  s.tracked = {{0}};
  s.singular = {0, 0, 0};
  s.input.vertices = {input[0], input[1], input[2]};
  s.input.faces = {{0, 1, 2}};
  const double uv[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  for (int k = 0; k < 3; ++k) s.points.push_back({input[k], 0, MapPoint{0, uv[k][0], uv[k][1]}});
  return s;
}

Shell flat_prism() { return one_prism({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}); }

// The candidate that re-proposes prism 0, with vertex v moved.
StarCandidate move_vertex(const Shell& s, int v, const Vec3& bottom, const Vec3& middle, const Vec3& top) {
  StarCandidate c;
  c.op = OpKind::smooth;
  c.removed = {0};
  c.faces = {s.faces[0]};
  c.moved = {v};
  c.moved_bottom = {bottom};
  c.moved_middle = {middle};
  c.moved_top = {top};
  return c;
}

std::optional<Rejection> run(Shell& s, StarCandidate c, double epsilon = 10, double quality = 100,
                             const MiddleFit* fit = nullptr,
                             double slab_quality = std::numeric_limits<double>::infinity()) {
  ShellEditor editor(s);
  const LinearMiddle linear;
  const StarContext ctx{editor, fit ? *fit : linear, epsilon, quality, slab_quality};
  return check_candidate(default_star_invariants(), ctx, c);
}

} // namespace

TEST(CoarsenInvariants, IdentityIsAccepted) {
  Shell s = flat_prism();
  const auto why = run(s, move_vertex(s, 0, s.bottom[0], s.middle[0], s.top[0]));
  EXPECT_FALSE(why.has_value()) << to_string(*why);
}

TEST(CoarsenInvariants, SingularAdjacentRejected) {
  Shell s = flat_prism();
  s.singular = {1, 1, 0};
  EXPECT_EQ(run(s, move_vertex(s, 2, s.bottom[2], s.middle[2], s.top[2])), Rejection::singular_adjacent);
}

TEST(CoarsenInvariants, QualityRejected) {
  Shell s = flat_prism();
  // Vertex 1 pulled out to (5, 0): a needle; bound 1 < old max 1.15.
  const Vec3 d(4, 0, 0);
  EXPECT_EQ(run(s, move_vertex(s, 1, s.bottom[1] + d, s.middle[1] + d, s.top[1] + d), 10, 1.0), Rejection::quality);
}

// Three prisms in a strip: f0 (0, 1, 2) a needle of MIPS 14.4, f1 (1, 3, 2)
// and f2 (2, 3, 4) about 1. Moving vertex 4 makes f2 a needle of MIPS 5.7:
// below the star's worst (f0), but worse than every old face it shares an
// edge with (f1 and f2 itself: 1.4 at most). Bounded by the star's worst
// alone, needles grew along the input's short edges (abc_00000001, cheese).
TEST(CoarsenInvariants, QualityRejectedAcrossAnEdgeNotByTheStarsWorst) {
  Shell s;
  const Vec3 at[5] = {{0, 0, 0}, {1, 0, 0}, {0.5, 0.03, 0}, {1.2, 0.8, 0}, {0.4, 1.0, 0}};
  const Vec3 up(0, 0, 1);
  for (const auto& p : at) {
    s.middle.push_back(p);
    s.bottom.push_back(p - up);
    s.top.push_back(p + up);
  }
  s.faces = {{0, 1, 2}, {1, 3, 2}, {2, 3, 4}};
  s.tracked = {{0}, {1}, {2}};
  s.singular = {0, 0, 0, 0, 0};
  s.input.vertices = s.middle;
  s.input.faces = s.faces;
  const MapPoint image[5] = {{0, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {2, 0, 1}};
  for (int v = 0; v < 5; ++v) s.points.push_back({at[v], image[v].prism, image[v]});
  StarCandidate c;
  c.op = OpKind::smooth;
  c.removed = {0, 1, 2};
  c.faces = s.faces;
  c.moved = {4};
  const Vec3 needle(0.791, 0.469, 0);
  c.moved_bottom = {needle - up};
  c.moved_middle = {needle};
  c.moved_top = {needle + up};
  EXPECT_EQ(run(s, c, 10, 2.0), Rejection::quality);
}

TEST(CoarsenInvariants, SlabQualityRejected) {
  // Lowering the middle of vertex 0 to z = -0.99 flattens the lower slab's
  // tets on pillar 0 (AMIPS far above 60; the unit slab's worst is about 6).
  Shell s = flat_prism();
  const auto flatten = move_vertex(s, 0, s.bottom[0], Vec3(0, 0, -0.99), s.top[0]);
  EXPECT_EQ(run(s, flatten, 10, 100, nullptr, 60.0), Rejection::slab_quality);
  // Without the bound (the default) the same move passes this rule.
  EXPECT_NE(run(s, flatten), Rejection::slab_quality);
}

TEST(CoarsenInvariants, ThicknessRejected) {
  // The solid is 0.5 thick under every vertex; vertex 1 pulled out to
  // (3, 0) makes an edge of 3.2 = 6.3 x 0.5, the old worst was 2.8.
  Shell s = flat_prism();
  const Vec3 d(2, 0, 0);
  const auto stretch = move_vertex(s, 1, s.bottom[1] + d, s.middle[1] + d, s.top[1] + d);
  ShellEditor editor(s);
  const LinearMiddle linear;
  const std::vector<double> thickness(3, 0.5);
  StarContext ctx{editor, linear, 10, 100};
  ctx.thickness = &thickness;
  ctx.thickness_ratio = 4;
  auto c = stretch;
  EXPECT_EQ(check_candidate(default_star_invariants(), ctx, c), Rejection::thickness);
  ctx.thickness_ratio = 7; // the stretched triangle fits
  c = stretch;
  EXPECT_NE(check_candidate(default_star_invariants(), ctx, c), Rejection::thickness);
}

TEST(CoarsenInvariants, PositivityRejected) {
  Shell s = flat_prism();
  // The middle of vertex 0 above its top: the bottom slab inverts... and the top one.
  EXPECT_EQ(run(s, move_vertex(s, 0, s.bottom[0], Vec3(0, 0, 2), s.top[0])), Rejection::prism_positivity);
}

TEST(CoarsenInvariants, CoverageRejected) {
  // Input at height 0.9; lowering the top of vertex 0 to 0.5 makes the top
  // cap cut through it.
  Shell s = one_prism({Vec3(0.1, 0.1, 0.9), Vec3(0.8, 0.1, 0.9), Vec3(0.1, 0.8, 0.9)});
  EXPECT_EQ(run(s, move_vertex(s, 0, s.bottom[0], s.middle[0], Vec3(0, 0, 0.5))), Rejection::coverage);
}

TEST(CoarsenInvariants, SectionRejected) {
  // An input triangle facing down (clockwise from the top) is no section.
  Shell s = one_prism({Vec3(0.1, 0.1, 0.5), Vec3(0.1, 0.6, 0.5), Vec3(0.6, 0.1, 0.5)});
  EXPECT_EQ(run(s, move_vertex(s, 0, s.bottom[0], s.middle[0], s.top[0])), Rejection::section);
}

TEST(CoarsenInvariants, CapsIntersectionRejected) {
  // Two prisms stacked: A (vertices 0-2) at z in [-1, 1], B (3-5) at z in
  // [2, 4] over the same triangle. Lowering B's bottom corner 3 to z = 0.5
  // pushes B's bottom cap through A's top cap.
  Shell s = flat_prism();
  const Vec3 base[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (int k = 0; k < 3; ++k) {
    s.bottom.push_back(base[k] + Vec3(0, 0, 2));
    s.middle.push_back(base[k] + Vec3(0, 0, 3));
    s.top.push_back(base[k] + Vec3(0, 0, 4));
    s.singular.push_back(0);
    s.input.vertices.push_back(base[k] + Vec3(0, 0, 3));
  }
  s.faces.push_back({3, 4, 5});
  s.input.faces.push_back({3, 4, 5});
  s.tracked.push_back({1});
  StarCandidate c;
  c.removed = {1};
  c.faces = {s.faces[1]};
  c.moved = {3};
  c.moved_bottom = {Vec3(0, 0, 0.5)};
  c.moved_middle = {s.middle[3]};
  c.moved_top = {s.top[3]};
  EXPECT_EQ(run(s, c), Rejection::caps_intersection);
}

TEST(CoarsenInvariants, CurvedFitExtensionPointIsConsulted) {
  struct RejectingFit final : MiddleFit {
    int degree() const override { return 1; }
    bool fit_and_check(const ShellEditor&, StarCandidate&, double) const override { return false; }
    Vec3 evaluate(const StarCandidate&, int, double, double) const override { return Vec3::Zero(); }
    std::vector<Vec3> patch_nodes(const StarCandidate&, int) const override { return {}; }
  };
  Shell s = flat_prism();
  const RejectingFit fit;
  EXPECT_EQ(run(s, move_vertex(s, 0, s.bottom[0], s.middle[0], s.top[0]), 10, 100, &fit), Rejection::curved_fit);
}

TEST(CoarsenInvariants, DistanceRejected) {
  // Raising the middle of vertex 0 by 0.5 moves the image of input vertex 0
  // (still Π = corner 0) 0.5 away: rejected for epsilon 0.1, accepted for 1.
  Shell s = flat_prism();
  const auto c = move_vertex(s, 0, s.bottom[0], Vec3(0, 0, 0.5), s.top[0]);
  EXPECT_EQ(run(s, c, 0.1), Rejection::distance);
  EXPECT_FALSE(run(s, c, 1.0).has_value());
}

// Each operation accepted and rejected on tiny shells (built by build_shell
// from small closed meshes), and a collapse that would fold the middle over.
#include "tiny_meshes.hpp"

#include "curvetet/shell/build.hpp"
#include "curvetet/shell/coarsen.hpp"
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/operations.hpp"
#include "curvetet/shell/shell_editor.hpp"
#include "curvetet/shell/star_invariants.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace curvetet;
using namespace curvetet::shell;

namespace {

// A "dart": apex a = 0 at the origin with a flat fan of 6 ring vertices in
// z = 0 whose ring is star-shaped around a but not around r0; a cone from the
// ring down to vertex 7 = (0, 0, -1) closes it.
//
//            r2 (0,1)
//           /  \            r1 = 0.5 at 30 deg, r5 = 0.5 at -30 deg:
//   r3 ---- a -- r1 ------ r0 (2,0)      collapsing a into r0 turns
//           \  /            (a, r1, r2) into (r0, r1, r2), clockwise:
//            r4 (0,-1)      the middle folds over.
mesh::SurfaceMesh dart() {
  mesh::SurfaceMesh m;
  const double c30 = std::cos(M_PI / 6), s30 = std::sin(M_PI / 6);
  m.vertices = {{0, 0, 0},          {2, 0, 0},   {0.5 * c30, 0.5 * s30, 0}, {0, 1, 0}, {-1, 0, 0},
                {0, -1, 0},         {0.5 * c30, -0.5 * s30, 0}, {0, 0, -1}};
  for (int i = 0; i < 6; ++i) {
    const int r = 1 + i, rn = 1 + (i + 1) % 6;
    m.faces.push_back({0, r, rn});
    m.faces.push_back({7, rn, r});
  }
  return m;
}

struct Fixture {
  Shell shell;
  std::unique_ptr<ShellEditor> editor;
  LinearMiddle linear;
  InvariantList invariants = default_star_invariants();
  double epsilon, quality = 1e9;

  explicit Fixture(const mesh::SurfaceMesh& m, double eps_rel = 1.0) {
    shell = build_shell(m).shell;
    epsilon = eps_rel * mesh::bbox_diagonal(m.vertices);
    editor = std::make_unique<ShellEditor>(shell);
  }
  std::optional<Rejection> check(StarCandidate& c) const {
    const StarContext ctx{*editor, linear, epsilon, quality};
    return check_candidate(invariants, ctx, c);
  }
  void commit(const StarCandidate& c) {
    editor->commit(c, 0);
    editor->compact();
  }
  void expect_valid() const {
    EXPECT_TRUE(check_shell(shell).empty());
    const auto m = check_map(shell);
    EXPECT_LT(m.max_distance, epsilon);
    EXPECT_EQ(m.points_outside, 0);
    EXPECT_EQ(m.prisms_not_tiled, 0) << "prism " << m.worst_prism << ", area error " << m.max_area_error;
    EXPECT_EQ(m.prisms_folded, 0) << "min piece " << m.min_piece_area;
  }
};

// Coarsens a sphere(3) shell with a loose bound, then checks every candidate
// of `make` at vertex/edge ids with a tiny bound: all rejected by distance.
template <class Make>
void expect_rejected_by_tiny_epsilon(Make&& make) {
  Shell s = build_shell(test::sphere(3)).shell;
  CoarsenOptions o;
  o.epsilon = 0.05;
  o.max_rounds = 1;
  coarsen_shell(s, o);
  ShellEditor editor(s);
  const LinearMiddle linear;
  const StarContext ctx{editor, linear, 1e-9, 1e9};
  const auto list = default_star_invariants();
  // Every candidate touching a prism with a mapped point is rejected (the
  // coarse middle is off the input there); those touching none may pass.
  int by_distance = 0;
  for (int v = 0; v < s.num_vertices(); ++v)
    for (auto& c : make(editor, v)) {
      bool has_points = false; // a point already off the middle surface
      for (int f : c.removed)
        for (int p : editor.points_in(f)) {
          const auto& pt = s.points[p];
          const PrismGeom g = prism_geom(s, f);
          const Vec3 x = (1 - pt.image.u - pt.image.v) * g.middle[0] + pt.image.u * g.middle[1] + pt.image.v * g.middle[2];
          has_points = has_points || (x - pt.position).norm() >= 1e-9;
        }
      const auto why = check_candidate(list, ctx, c);
      if (has_points) {
        EXPECT_TRUE(why.has_value());
      }
      by_distance += why == Rejection::distance;
    }
  EXPECT_GT(by_distance, 0);
}

} // namespace

TEST(CoarsenOps, CollapseAccepted) {
  Fixture f(test::sphere(3));
  const int faces = f.shell.num_prisms();
  std::optional<StarCandidate> accepted;
  for (int v = 0; v < f.shell.num_vertices() && !accepted; ++v)
    for (int w : f.editor->neighbours(v)) {
      auto c = collapse_candidate(*f.editor, v, w);
      if (!c) continue;
      if (!f.check(*c)) {
        accepted = std::move(c);
        break;
      }
    }
  ASSERT_TRUE(accepted.has_value());
  f.commit(*accepted);
  EXPECT_EQ(f.shell.num_prisms(), faces - 2);
  f.expect_valid();
}

TEST(CoarsenOps, CollapseFoldingTheMiddleIsRejected) {
  Fixture f(dart());
  ASSERT_FALSE(f.shell.singular[0]);
  auto c = collapse_candidate(*f.editor, 0, 1);
  ASSERT_TRUE(c.has_value()); // topologically fine
  EXPECT_EQ(f.check(*c), Rejection::prism_positivity);
}

TEST(CoarsenOps, CollapseTopologyRejected) {
  Fixture f(test::octahedron());
  // Opposite vertices 0 and 2 share no edge.
  EXPECT_FALSE(collapse_candidate(*f.editor, 0, 2).has_value());
  EXPECT_TRUE(collapse_candidate(*f.editor, 0, 1).has_value());
  // Triangular bipyramid: equator 0, 1, 2, apexes 3 (top), 4 (bottom).
  // Edge (0, 1): common neighbours {2, 3, 4} (link condition fails).
  mesh::SurfaceMesh bi;
  bi.vertices = {{1, 0, 0}, {-0.5, 0.8, 0}, {-0.5, -0.8, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 3; ++i) {
    bi.faces.push_back({i, (i + 1) % 3, 3});
    bi.faces.push_back({(i + 1) % 3, i, 4});
  }
  Fixture g(bi);
  EXPECT_FALSE(collapse_candidate(*g.editor, 0, 1).has_value());
  EXPECT_FALSE(collapse_candidate(*g.editor, 1, 0).has_value());
}

TEST(CoarsenOps, CollapseRejectedByDistance) {
  expect_rejected_by_tiny_epsilon([](const ShellEditor& e, int v) {
    std::vector<StarCandidate> out;
    for (int w : e.neighbours(v))
      if (auto c = collapse_candidate(e, v, w)) out.push_back(std::move(*c));
    return out;
  });
}

TEST(CoarsenOps, FlipAccepted) {
  Fixture f(test::sphere(3));
  int accepted = 0;
  for (int v = 0; v < f.shell.num_vertices() && !accepted; ++v)
    for (int w : f.editor->neighbours(v)) {
      auto c = flip_candidate(*f.editor, v, w);
      if (!c || f.check(*c)) continue;
      f.commit(*c);
      ++accepted;
      break;
    }
  EXPECT_EQ(accepted, 1);
  f.expect_valid();
}

TEST(CoarsenOps, FlipOfNonConvexQuadRejected) {
  // Edge (a, r1) of the dart: its quad a, r0, r1, r2 is not convex at r1.
  Fixture f(dart());
  auto c = flip_candidate(*f.editor, 0, 2);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(f.check(*c), Rejection::prism_positivity);
}

TEST(CoarsenOps, FlipRejectedByDistance) {
  expect_rejected_by_tiny_epsilon([](const ShellEditor& e, int v) {
    std::vector<StarCandidate> out;
    for (int w : e.neighbours(v))
      if (auto c = flip_candidate(e, v, w)) out.push_back(std::move(*c));
    return out;
  });
}

TEST(CoarsenOps, SplitAcceptedAtAnInputPoint) {
  Fixture f(test::sphere(3));
  const int v = 0, w = f.editor->neighbours(0)[0];
  auto c = split_candidate(*f.editor, v, w);
  ASSERT_TRUE(c.has_value());
  // The new middle vertex lies on the input surface (the unit sphere's chords).
  const auto why = f.check(*c);
  ASSERT_FALSE(why.has_value()) << to_string(*why);
  const int faces = f.shell.num_prisms();
  f.commit(*c);
  EXPECT_EQ(f.shell.num_prisms(), faces + 2);
  f.expect_valid();
}

TEST(CoarsenOps, SplitRejectedByQualityRule) {
  Fixture f(test::sphere(3));
  f.quality = 1.0; // halves of a near-equilateral triangle are worse
  auto c = split_candidate(*f.editor, 0, f.editor->neighbours(0)[0]);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(f.check(*c), Rejection::quality);
}

TEST(CoarsenOps, SplitRejectedByDistance) {
  expect_rejected_by_tiny_epsilon([](const ShellEditor& e, int v) {
    std::vector<StarCandidate> out;
    for (int w : e.neighbours(v))
      if (auto c = split_candidate(e, v, w)) out.push_back(std::move(*c));
    return out;
  });
}

TEST(CoarsenOps, SmoothAccepted) {
  Fixture f(test::sphere(3));
  // The pillars are far below a huge zoom target: "zoom" proposes x1.5.
  SmoothParams p{10.0, 1e-3};
  auto cands = smooth_candidates(*f.editor, 0, p);
  ASSERT_FALSE(cands.empty());
  bool done = false;
  for (auto& c : cands)
    if (!f.check(c)) {
      f.commit(c);
      done = true;
      break;
    }
  EXPECT_TRUE(done);
  f.expect_valid();
}

TEST(CoarsenOps, SmoothRejectedByDistance) {
  expect_rejected_by_tiny_epsilon(
      [](const ShellEditor& e, int v) { return smooth_candidates(e, v, SmoothParams{10.0, 1e-3}); });
}

// The reports' rejection counts: every reason named, summed over passes.
TEST(CoarsenOps, RejectionsJsonNamesEveryReasonAndSumsPasses) {
  PassStats a, b;
  a.rejected[static_cast<int>(Rejection::distance)] = 3;
  b.rejected[static_cast<int>(Rejection::distance)] = 4;
  b.rejected[static_cast<int>(Rejection::surface_distance)] = 5;
  const auto one = rejections_json(a), both = rejections_json(std::vector<PassStats>{a, b});
  EXPECT_EQ(static_cast<int>(both.size()), kRejectionCount);
  EXPECT_EQ(one["distance"].get<long long>(), 3);
  EXPECT_EQ(both["distance"].get<long long>(), 7);
  EXPECT_EQ(both["surface_distance"].get<long long>(), 5);
  EXPECT_EQ(both["quality"].get<long long>(), 0);
}

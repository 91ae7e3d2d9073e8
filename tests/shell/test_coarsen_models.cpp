// Coarsening on real meshes from ../shared/data (good, without features):
// the global checker after every pass (--debug-invariants) on the small
// ones, the distance bound and the bijectivity of the map at the end, and
// identical output for 1 and 2 threads. Bigger sweeps: bench/.
#include "tiny_meshes.hpp"

#include "curvetet/core/threads.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/shell/build.hpp"
#include "curvetet/shell/coarsen.hpp"
#include "curvetet/shell/curved_middle.hpp"
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/star_invariants.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

using namespace curvetet;
using namespace curvetet::shell;

namespace {

mesh::SurfaceMesh load(const std::string& name) {
  return mesh::to_surface_mesh(io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/" + name));
}

void expect_valid_coarse_shell(const Shell& s, const CoarsenStats& st) {
  EXPECT_TRUE(check_shell(s).empty());
  const auto m = check_map(s);
  EXPECT_LT(m.max_distance, st.epsilon) << "point " << m.worst_point;
  EXPECT_EQ(m.points_outside, 0);
  EXPECT_EQ(m.prisms_not_tiled, 0) << "prism " << m.worst_prism << ", area error " << m.max_area_error;
  EXPECT_EQ(m.prisms_folded, 0) << "min piece " << m.min_piece_area;
  // Every input vertex is a constraint point with a stored image.
  ASSERT_GE(s.points.size(), std::size_t(s.input.num_vertices()));
}

} // namespace

// The global checker after every pass (throws on any violation).
TEST(CoarsenModels, DebugInvariantsOnSmallModel) {
  auto built = build_shell(load("thingi10k_288351.off"));
  CoarsenOptions o;
  o.debug_invariants = true;
  const auto st = coarsen_shell(built.shell, o);
  expect_valid_coarse_shell(built.shell, st);
  EXPECT_LE(st.faces_after, st.faces_before + st.faces_before / 10);
}

TEST(CoarsenModels, DebugInvariantsOnSphere) {
  auto built = build_shell(test::sphere(4));
  CoarsenOptions o;
  o.debug_invariants = true;
  const auto st = coarsen_shell(built.shell, o);
  expect_valid_coarse_shell(built.shell, st);
  EXPECT_LT(st.faces_after * 4, st.faces_before);
}

// The slab rule under the global checker, with a bound it must enforce (the
// sphere coarsened without it reaches a worst slab of 12.15): the worst lower
// slab never exceeds max(the uncoarsened shell's worst, 7.5); and the last
// pass is no split (it would leave faces behind).
TEST(CoarsenModels, SlabRuleBoundsTheWorstSlab) {
  auto built = build_shell(test::sphere(4));
  const auto worst_slab = [](const Shell& s) {
    double w = 0;
    for (const auto& f : s.faces)
      w = std::max(w, lower_slab_amips({s.bottom[f[0]], s.bottom[f[1]], s.bottom[f[2]]},
                                       {s.middle[f[0]], s.middle[f[1]], s.middle[f[2]]}));
    return w;
  };
  const double before = worst_slab(built.shell);
  CoarsenOptions o;
  o.debug_invariants = true;
  o.slab_quality_bound = 7.5;
  const auto st = coarsen_shell(built.shell, o);
  expect_valid_coarse_shell(built.shell, st);
  EXPECT_LT(st.faces_after * 2, st.faces_before);
  EXPECT_LE(worst_slab(built.shell), std::max(before, 7.5));
  std::printf("worst slab before %g after %g, %d -> %d faces\n", before, worst_slab(built.shell), st.faces_before,
              st.faces_after);
  ASSERT_FALSE(st.passes.empty());
  EXPECT_NE(st.passes.back().op, OpKind::split);
}

namespace {

void expect_same_shell(const Shell& a, const Shell& b) {
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.middle_nodes, b.middle_nodes);
  EXPECT_EQ(a.tracked, b.tracked);
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  for (int v = 0; v < a.num_vertices(); ++v) {
    EXPECT_EQ(a.bottom[v], b.bottom[v]);
    EXPECT_EQ(a.middle[v], b.middle[v]);
    EXPECT_EQ(a.top[v], b.top[v]);
  }
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].image.prism, b.points[i].image.prism);
    EXPECT_EQ(a.points[i].image.u, b.points[i].image.u);
    EXPECT_EQ(a.points[i].image.v, b.points[i].image.v);
  }
}

} // namespace

TEST(CoarsenModels, SameResultForOneAndTwoThreads) {
  const auto input = test::sphere(4);
  Shell a = build_shell(input).shell, b = a;
  CoarsenOptions o;
  {
    ThreadLimit one(1);
    coarsen_shell(a, o);
  }
  {
    ThreadLimit two(2);
    coarsen_shell(b, o);
  }
  expect_same_shell(a, b);
}

// Rejections replayed from the memo stand for checks that would reject
// again: the shell, and the rejection counts, are those of checking every
// entry. With the curved middle and the thickness rule, whose state the
// star's signature must cover.
TEST(CoarsenModels, RememberedRejectionsChangeNothing) {
  Shell a = build_shell(test::sphere(4)).shell, b = a;
  CoarsenOptions o;
  o.thickness_ratio = 4;
  const CurvedMiddleFit fit(3);
  const auto with = coarsen_shell(a, o, &fit);
  o.remember_rejections = false;
  const auto without = coarsen_shell(b, o, &fit);
  long long remembered = 0;
  ASSERT_EQ(with.passes.size(), without.passes.size());
  for (std::size_t i = 0; i < with.passes.size(); ++i) {
    remembered += with.passes[i].remembered;
    EXPECT_EQ(without.passes[i].remembered, 0);
    EXPECT_EQ(with.passes[i].tried, without.passes[i].tried) << "pass " << i;
    EXPECT_EQ(with.passes[i].rejected, without.passes[i].rejected) << "pass " << i;
  }
  EXPECT_GT(remembered, 0);
  expect_same_shell(a, b);
}

// Acceptance figure: >= 8x fewer faces on the bunny at epsilon = 1% with a
// linear middle, valid shell, every input vertex within epsilon, bijective.
TEST(CoarsenModels, BunnyReduction) {
  auto built = build_shell(load("bunny_libigl.off"));
  const auto st = coarsen_shell(built.shell, CoarsenOptions{});
  EXPECT_GE(st.faces_before, 8 * st.faces_after);
  expect_valid_coarse_shell(built.shell, st);
}

// Shell construction: singular vertices, isolation, validity, the map and Π.
#include "tiny_meshes.hpp"

#include "curvetet/check/preconditions.hpp"
#include "curvetet/core/threads.hpp"
#include "curvetet/mesh/edge_topology.hpp"
#include "curvetet/shell/build.hpp"
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/projection.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace curvetet;
using namespace curvetet::shell;

namespace {

void expect_no_adjacent_singular(const Shell& s) {
  for (const auto& e : mesh::build_edge_topology(s.faces).edges)
    EXPECT_FALSE(s.singular[e[0]] && s.singular[e[1]]) << "edge " << e[0] << "-" << e[1];
}

// Π is the identity at input vertices, and Π⁻¹(Π(p)) = p for random points.
void expect_projection_round_trip(const Shell& s, int samples, unsigned seed) {
  const Projector pi(s);
  for (int i = 0; i < s.input.num_vertices(); ++i) {
    const auto& p = s.points[i];
    const MapPoint m = pi.project(p.position, p.input_face);
    EXPECT_LT((pi.middle_point(m) - p.position).norm(), 1e-12) << "vertex " << i;
    EXPECT_LT((pi.middle_point(p.image) - p.position).norm(), 1e-12) << "stored image of vertex " << i;
    const auto back = pi.unproject(p.image);
    ASSERT_TRUE(back.has_value()) << "vertex " << i;
    EXPECT_LT((*back - p.position).norm(), 1e-12) << "vertex " << i;
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::uniform_int_distribution<int> F(0, s.input.num_faces() - 1);
  for (int k = 0; k < samples; ++k) {
    const int f = F(rng);
    double a = U(rng), b = U(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const auto& t = s.input.faces[f];
    const Vec3 p = (1 - a - b) * s.input.vertices[t[0]] + a * s.input.vertices[t[1]] + b * s.input.vertices[t[2]];
    const MapPoint m = pi.project(p, f);
    const auto back = pi.unproject(m);
    ASSERT_TRUE(back.has_value());
    EXPECT_LT((*back - p).norm(), 1e-12) << "face " << f;
  }
}

} // namespace

TEST(BuildShell, SphereIsValidAndReachesTheTarget) {
  const auto m = test::sphere(3);
  ShellOptions o;
  o.debug_invariants = true; // global check after each stage (throws)
  const auto b = build_shell(m, o);
  EXPECT_TRUE(check_shell(b.shell).empty());
  EXPECT_EQ(b.stats.singular_vertices, 0);
  EXPECT_EQ(b.stats.vertices_at_target, m.num_vertices());
  EXPECT_NEAR(b.stats.min_pillar, 0.02 * mesh::bbox_diagonal(m.vertices), 1e-15);
  // Bottom inside, top outside the unit sphere.
  for (int v = 0; v < m.num_vertices(); ++v) {
    EXPECT_LT(b.shell.bottom[v].norm(), 1);
    EXPECT_GT(b.shell.top[v].norm(), 1);
  }
  expect_projection_round_trip(b.shell, 500, 1);
}

TEST(BuildShell, FoldedStarCentreIsSingularPinchedAndIsolated) {
  const auto m = test::folded_star();
  // The test mesh is a valid input.
  ASSERT_TRUE(check::check_preconditions(mesh::to_soup(m)).ok());
  EXPECT_TRUE(extrusion_directions(m, 1e-3)[0].singular);
  ShellOptions o;
  o.debug_invariants = true;
  const auto b = build_shell(m, o);
  const Shell& s = b.shell;
  EXPECT_TRUE(check_shell(s).empty());
  ASSERT_TRUE(s.singular[0]);
  EXPECT_GE(b.stats.singular_vertices, 1);
  // Pinched: B = V = T exactly at the apex.
  EXPECT_EQ(s.top[0], s.middle[0]);
  EXPECT_EQ(s.bottom[0], s.middle[0]);
  expect_no_adjacent_singular(s);
  for (int v = 0; v < s.num_vertices(); ++v)
    if (!s.singular[v]) {
      EXPECT_NE(s.top[v], s.middle[v]);
    }
  expect_projection_round_trip(s, 300, 2);
}


TEST(BuildShell, AdjacentSingularVerticesAreSplitApart) {
  // With a high singularity threshold (min n.d < 0.3) the folded star's
  // centre and four of its ring vertices (min n.d ~ 0.25) are singular and
  // adjacent: the edges between them are split before building.
  const auto m = test::folded_star();
  ShellOptions o;
  o.extrusion.singular_dot = 0.3;
  o.debug_invariants = true;
  const auto dirs = extrusion_directions(m, 0.3);
  int adjacent = 0;
  for (const auto& e : mesh::build_edge_topology(m.faces).edges) adjacent += dirs[e[0]].singular && dirs[e[1]].singular;
  ASSERT_GT(adjacent, 0);
  const auto b = build_shell(m, o);
  EXPECT_EQ(b.stats.split_edges, adjacent);
  EXPECT_GT(b.shell.num_prisms(), m.num_faces());
  EXPECT_TRUE(check_shell(b.shell).empty());
  expect_no_adjacent_singular(b.shell);
  // Input vertices keep their ids and positions; split faces track their
  // input face (both halves).
  for (int i = 0; i < m.num_vertices(); ++i) EXPECT_EQ(b.shell.middle[i], m.vertices[i]);
  for (int f = 0; f < b.shell.num_prisms(); ++f) ASSERT_EQ(b.shell.tracked[f].size(), 1u);
  expect_projection_round_trip(b.shell, 300, 3);
}

TEST(BuildShell, SameResultForOneAndTwoThreads) {
  const auto m = test::sphere(3);
  ShellOptions o;
  o.extrusion.target_thickness = 0.4; // beyond the radius: many rejected growths
  ShellBuild one, two;
  {
    curvetet::ThreadLimit limit(1);
    one = build_shell(m, o);
  }
  {
    curvetet::ThreadLimit limit(2);
    two = build_shell(m, o);
  }
  EXPECT_GT(one.stats.reverts, 0);
  EXPECT_EQ(one.shell.top, two.shell.top);
  EXPECT_EQ(one.shell.bottom, two.shell.bottom);
}

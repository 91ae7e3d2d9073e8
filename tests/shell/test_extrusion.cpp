// Extrusion directions (active-set QP), singular detection, one-sided layers.
#include "tiny_meshes.hpp"

#include "curvetet/geometry/predicates.hpp"
#include "curvetet/shell/extrusion.hpp"
#include "curvetet/shell/invariants.hpp"
#include "curvetet/shell/layer_growth.hpp"
#include "curvetet/shell/prism_tets.hpp"

#include <gtest/gtest.h>

#include <atomic>

using namespace curvetet;
using namespace curvetet::shell;

TEST(ExtrusionDirection, SingleFaceIsItsNormal) {
  auto r = extrusion_direction({Vec3(0, 0, 1)}, 1e-3);
  EXPECT_FALSE(r.singular);
  EXPECT_NEAR((r.direction - Vec3(0, 0, 1)).norm(), 0, 1e-15);
}

TEST(ExtrusionDirection, TwoActiveFacesGiveTheBisector) {
  // A roof ridge: normals (±s, 0, c); a third face (0,0,1) is inactive.
  const double s = std::sin(0.6), c = std::cos(0.6);
  auto r = extrusion_direction({Vec3(s, 0, c), Vec3(-s, 0, c), Vec3(0, 0, 1)}, 1e-3);
  EXPECT_FALSE(r.singular);
  EXPECT_NEAR((r.direction - Vec3(0, 0, 1)).norm(), 0, 1e-12);
  EXPECT_NEAR(r.min_dot, c, 1e-12);
}

TEST(ExtrusionDirection, ThreeActiveFacesOfACubeCorner) {
  auto r = extrusion_direction({Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}, 1e-3);
  EXPECT_FALSE(r.singular);
  EXPECT_NEAR((r.direction - Vec3(1, 1, 1).normalized()).norm(), 0, 1e-12);
  EXPECT_NEAR(r.min_dot, 1 / std::sqrt(3.0), 1e-12);
}

TEST(ExtrusionDirection, OpposedNormalsAreSingular) {
  // Zero is a positive combination of the normals: no direction sees all
  // three faces (infeasible QP).
  EXPECT_TRUE(extrusion_direction({Vec3(0, 0, 1), Vec3(0.1, 0, -1).normalized(), Vec3(-0.1, 0, -1).normalized()},
                                  1e-3)
                  .singular);
  // Two faces that are not exactly opposed are always seen by some direction.
  EXPECT_FALSE(extrusion_direction({Vec3(0, 0, 1), Vec3(0, 0.1, -1).normalized()}, 1e-3).singular);
  // Feasible but nearly tangent (min dot below the threshold): singular too.
  const double e = 1e-4;
  EXPECT_TRUE(extrusion_direction({Vec3(1, 0, e).normalized(), Vec3(-1, 0, e).normalized()}, 1e-3).singular);
}

namespace {

// Independent re-check of extrude_one_sided's guarantees (header contract).
void expect_valid_layer(const mesh::SurfaceMesh& m, const OneSidedExtrusion& x, Side side) {
  ASSERT_EQ(x.offset.size(), m.vertices.size());
  for (int v = 0; v < m.num_vertices(); ++v) {
    EXPECT_EQ(x.offset[v], Vec3(m.vertices[v] + x.length[v] * x.direction[v]));
    if (x.singular[v]) {
      EXPECT_EQ(x.length[v], 0);
    } else {
      EXPECT_GT(x.length[v], 0);
    }
  }
  // 1. positivity of the 12 tets per face, lower/upper per the contract.
  for (const auto& f : m.faces)
    for (const auto& tet : all_slab_tets()) {
      if (x.length[f[tet.pillar]] == 0) continue;
      Vec3 p[4];
      for (int i = 0; i < 4; ++i) {
        const int c = tet.corners[i];
        const bool upper = c >= 3;
        const bool on_offset = (side == Side::outward) == upper;
        const int v = f[c % 3];
        p[i] = on_offset ? x.offset[v] : m.vertices[v];
      }
      EXPECT_EQ(geometry::orient3d(p[0], p[1], p[2], p[3]), 1);
    }
  // 2. intersection-free union of surface and offset surface.
  Shell s;
  s.middle = m.vertices;
  s.faces = m.faces;
  s.bottom = side == Side::inward ? x.offset : m.vertices;
  s.top = side == Side::outward ? x.offset : m.vertices;
  EXPECT_TRUE(cap_intersections(s).empty());
}

} // namespace

TEST(OneSidedExtrusion, SphereInwardAndOutwardReachTheTarget) {
  const auto m = test::sphere(2);
  ExtrusionOptions o;
  o.target_thickness = 0.01;
  for (Side side : {Side::inward, Side::outward}) {
    const auto x = extrude_one_sided(m, side, o);
    expect_valid_layer(m, x, side);
    const double target = o.target_thickness * mesh::bbox_diagonal(m.vertices);
    EXPECT_NEAR(x.min_length, target, 1e-15);
    // Inward offsets shrink the sphere, outward ones grow it.
    for (int v = 0; v < m.num_vertices(); ++v)
      EXPECT_EQ(x.offset[v].norm() < 1, side == Side::inward);
  }
}

TEST(OneSidedExtrusion, LargeTargetStopsWherePrismsWouldInvert) {
  // Inward by more than the radius would invert the layer: growth must stop
  // early, everything still valid.
  const auto m = test::sphere(1);
  ExtrusionOptions o;
  o.target_thickness_abs = 5.0;
  const auto x = extrude_one_sided(m, Side::inward, o);
  expect_valid_layer(m, x, Side::inward);
  EXPECT_LT(x.max_length, 1.0);
  EXPECT_GT(x.min_length, 0.05);
}

TEST(OneSidedExtrusion, SingularVertexStaysOnTheSurface) {
  // The folded star's centre sees no common direction: zero-length pillar,
  // the offset vertex is the surface vertex, the layer is still valid.
  const auto m = test::folded_star();
  for (Side side : {Side::inward, Side::outward}) {
    const auto x = extrude_one_sided(m, side, {});
    ASSERT_TRUE(x.singular[0]);
    EXPECT_EQ(x.offset[0], m.vertices[0]);
    expect_valid_layer(m, x, side);
    EXPECT_GT(x.min_length, 0);
  }
}

TEST(OneSidedExtrusion, AdjacentSingularVerticesNeedNoSplit) {
  // With a high singularity threshold several adjacent vertices are
  // singular; the one-sided layer keeps the faces as they are.
  const auto m = test::folded_star();
  ExtrusionOptions o;
  o.singular_dot = 0.3;
  const auto x = extrude_one_sided(m, Side::outward, o);
  int singular = 0;
  for (char c : x.singular) singular += c;
  EXPECT_GE(singular, 2);
  expect_valid_layer(m, x, Side::outward);
}

// A stop requested during a check pass ends it at its next batch of exact
// cap-pair tests, not at the next pass: the layered fill's early extrusion
// is abandoned this way when the direct fill succeeds, and the fill waited
// for whole passes (thingi10k: up to 5 ms of a 50 ms run).
TEST(LayerGrowth, StopRequestedInsideACheckPassEndsIt) {
  const auto m = test::sphere(2);
  Shell s = flat_shell(m);
  LayerGrowthSpec spec;
  spec.grow_top = false;
  for (const auto& d : extrusion_directions(m, 1e-3)) spec.direction.push_back(d.direction);
  spec.initial = 0.01;
  spec.target = 0.05;
  std::vector<std::string> stages;
  spec.after_stage = [&](const Shell&, std::string_view stage) { stages.emplace_back(stage); };
  std::atomic<int> polls = 0; // polled from the worker threads too
  spec.stop_requested = [&] { return ++polls >= 2; }; // the pass's own poll, then those from inside it
  std::vector<double> len;
  EXPECT_THROW(grow_layer(s, spec, len), Stopped);
  EXPECT_TRUE(stages.empty()) << "stopped only after the initial layer's check pass";
  // Without a stop, the same growth completes both stages.
  spec.stop_requested = [] { return false; };
  grow_layer(s, spec, len);
  EXPECT_EQ(stages, (std::vector<std::string>{"initial layer", "thickening"}));
}

// Exactness of the boundary-preserving fill (issue 6 acceptance): doubles
// out, every tet positive by exact orient3d, boundary = input triangles (ids,
// coordinates bit for bit, orientation), interior faces shared by two tets,
// volume = enclosed volume.
#include "shapes.hpp"

#include "curvetet/volume/fill.hpp"
#include "curvetet/volume/verify.hpp"

#include <gtest/gtest.h>

namespace curvetet {
namespace {

mesh::LinearTetMesh expect_exact_interior(const volume::LayeredSurface& l, const volume::FillOptions& o = {}) {
  volume::FillStats stats;
  auto tm = volume::fill_layered(l, o, &stats);
  EXPECT_GE(tm.num_vertices(), l.surface.num_vertices());
  if (tm.num_vertices() < l.surface.num_vertices()) return tm;
  for (int v = 0; v < l.surface.num_vertices(); ++v) {
    // bit-identical coordinates
    EXPECT_EQ(std::memcmp(tm.vertices[v].data(), l.surface.vertices[v].data(), sizeof(double) * 3), 0) << v;
  }
  const auto check = volume::verify_tet_mesh(tm, l.surface.faces);
  EXPECT_TRUE(check.ok()) << check.text();
  const double vol = test::enclosed_volume(l.surface);
  EXPECT_NEAR(check.volume, vol, 1e-9 * std::abs(vol));
  return tm;
}

TEST(VolumeFill, CubeInteriorIsExact) {
  const auto cube = test::unit_cube();
  expect_exact_interior(test::scaled_offset(cube, {0.5, 0.5, 0.5}, 0.9));
}

TEST(VolumeFill, CubeInteriorWithoutOptimizationIsExact) {
  volume::FillOptions o;
  o.optimize_rounds = 0;
  expect_exact_interior(test::scaled_offset(test::unit_cube(), {0.5, 0.5, 0.5}, 0.9), o);
}

TEST(VolumeFill, OctahedronInteriorIsExact) {
  expect_exact_interior(test::scaled_offset(test::octahedron(), {0.1, -0.05, 0.02}, 0.7));
}

TEST(VolumeFill, IcosphereInteriorIsExact) {
  expect_exact_interior(test::scaled_offset(test::icosphere(2), {0, 0, 0}, 0.97));
}

// The pipeline's fill: collapses and flips (3-2, and edge removals followed
// by 3-2 flips) up to an energy bound remove tets and stay exact; a bound on
// new edge lengths keeps interior vertices (a finer interior).
TEST(VolumeFill, CoarseningRemovesTetsAndStaysExact) {
  const auto sphere = test::scaled_offset(test::icosphere(2), {0, 0, 0}, 0.97);
  const auto plain = expect_exact_interior(sphere);
  volume::FillOptions coarse;
  coarse.coarsen_energy = 100;
  const auto coarsest = expect_exact_interior(sphere, coarse);
  coarse.max_edge_length = 0.5; // the sphere's diameter is 2
  const auto sized = expect_exact_interior(sphere, coarse);
  const int n = sphere.surface.num_vertices();
  // Measured: 562 tets plain, 379 coarsened, none left inside.
  EXPECT_EQ(coarsest.num_vertices(), n);
  EXPECT_LT(coarsest.tets.size(), 0.75 * static_cast<double>(plain.tets.size()));
  EXPECT_GT(sized.num_vertices(), n);
  EXPECT_GT(sized.tets.size(), coarsest.tets.size());
  std::printf("icosphere fill: %zu tets plain, %zu coarsened, %zu with edges <= 0.5 (%d surface vertices)\n",
              plain.tets.size(), coarsest.tets.size(), sized.tets.size(), n);
}

TEST(VolumeFill, CubeExteriorIsExactUpToTheBox) {
  const auto l = test::scaled_offset(test::unit_cube(), {0.5, 0.5, 0.5}, 1.1);
  const auto tm = volume::fill_layered(l);
  std::vector<mesh::Tri> reversed;
  for (auto f : l.surface.faces) reversed.push_back({f[0], f[2], f[1]});
  Eigen::Vector3d lo = tm.vertices[0], hi = tm.vertices[0];
  for (const auto& p : tm.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const auto check = volume::verify_tet_mesh(tm, reversed, volume::Box{lo, hi});
  EXPECT_TRUE(check.ok()) << check.text();
  const double box = (hi - lo).prod();
  EXPECT_NEAR(check.volume, box - 1.0, 1e-9 * box);
}

} // namespace
} // namespace curvetet

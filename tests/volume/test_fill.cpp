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

void expect_exact_interior(const volume::LayeredSurface& l, const volume::FillOptions& o = {}) {
  volume::FillStats stats;
  const auto tm = volume::fill_layered(l, o, &stats);
  ASSERT_GE(tm.num_vertices(), l.surface.num_vertices());
  for (int v = 0; v < l.surface.num_vertices(); ++v) {
    // bit-identical coordinates
    EXPECT_EQ(std::memcmp(tm.vertices[v].data(), l.surface.vertices[v].data(), sizeof(double) * 3), 0) << v;
  }
  const auto check = volume::verify_tet_mesh(tm, l.surface.faces);
  EXPECT_TRUE(check.ok()) << check.text();
  const double vol = test::enclosed_volume(l.surface);
  EXPECT_NEAR(check.volume, vol, 1e-9 * std::abs(vol));
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

// Regression (nefertiti.off, issue 6): where the offset coincides with the
// surface (an edge whose two ends are pinched), the exact insertion can put
// Steiner points on the surface edge itself; the fill then had the two faces
// of that edge split (2 missing and 2+ extra boundary faces, exit 3). The
// optimizer must collapse such points along the edge. Reproduced here on the
// smallest case: a cube coned from its centre, one boundary edge split at its
// midpoint (as the insertion did), marked as a surface Steiner point.
#include "shapes.hpp"

#include "curvetet/volume/exact_mesh.hpp"
#include "curvetet/volume/optimize.hpp"
#include "curvetet/volume/verify.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

namespace curvetet {
namespace {

using volume::exact::ExactTetMesh;

// Cube [0,1]^3 coned from its centre; the boundary edge (a, b) is split at a
// rational point w on it (w = a + t (b - a)).
ExactTetMesh split_cube(const mesh::SurfaceMesh& cube, int a, int b, const mpq_class& t, int* w_id) {
  ExactTetMesh m;
  for (const auto& p : cube.vertices) m.v.add(p);
  const int c = m.v.add(mesh::Vec3(0.5, 0.5, 0.5));
  volume::exact::QPoint w;
  const auto qa = volume::exact::to_q(cube.vertices[a]), qb = volume::exact::to_q(cube.vertices[b]);
  for (int k = 0; k < 3; ++k) w.c[k] = qa.c[k] + t * (qb.c[k] - qa.c[k]);
  const int wi = m.v.add(w);
  auto add = [&](std::array<int, 4> q) {
    if (m.v.orient(q[0], q[1], q[2], q[3]) < 0) std::swap(q[0], q[1]);
    ASSERT_GT(m.v.orient(q[0], q[1], q[2], q[3]), 0);
    m.tets.push_back(q);
  };
  for (const auto& f : cube.faces) {
    const bool has_a = std::count(f.begin(), f.end(), a), has_b = std::count(f.begin(), f.end(), b);
    if (has_a && has_b) {
      const int x = f[0] != a && f[0] != b ? f[0] : (f[1] != a && f[1] != b ? f[1] : f[2]);
      add({a, wi, x, c});
      add({wi, b, x, c});
    } else {
      add({f[0], f[1], f[2], c});
    }
  }
  m.frozen.assign(m.v.size(), 0);
  for (int v = 0; v < cube.num_vertices(); ++v) m.frozen[v] = 1;
  m.on_surface.push_back({wi, {a, b}});
  *w_id = wi;
  return m;
}

// The first cube edge shared by two faces (an edge of the square sides).
std::array<int, 2> some_edge(const mesh::SurfaceMesh& cube) {
  const auto& f = cube.faces[0];
  return {f[0], f[1]};
}

void expect_boundary_restored(const mpq_class& t, int rounds) {
  const auto cube = test::unit_cube();
  const auto e = some_edge(cube);
  int w = -1;
  auto m = split_cube(cube, e[0], e[1], t, &w);
  // Before: the split faces are not the input faces (what nefertiti hit).
  {
    mesh::LinearTetMesh before;
    for (int v = 0; v < m.v.size(); ++v) before.vertices.push_back(m.v.d[v]);
    before.tets = m.tets;
    const auto c = volume::verify_tet_mesh(before, cube.faces);
    ASSERT_EQ(c.missing_boundary, 2u) << c.text();
  }
  volume::FillOptions o;
  o.optimize_rounds = rounds;
  volume::FillStats stats;
  const auto out = volume::exact::round_and_optimize(std::move(m), cube.num_vertices(), o, stats);
  for (int v = 0; v < cube.num_vertices(); ++v)
    EXPECT_EQ(std::memcmp(out.vertices[v].data(), cube.vertices[v].data(), 3 * sizeof(double)), 0) << v;
  const auto check = volume::verify_tet_mesh(out, cube.faces);
  EXPECT_TRUE(check.ok()) << check.text();
  EXPECT_NEAR(check.volume, 1.0, 1e-12);
}

TEST(VolumeSurfaceSteiner, MidpointOnEdgeIsCollapsed) { expect_boundary_restored(mpq_class(1, 2), 0); }

// A point that is not a double (1/3 of the way) and the full optimization.
TEST(VolumeSurfaceSteiner, RationalPointOnEdgeIsCollapsedWithOptimization) {
  expect_boundary_restored(mpq_class(1, 3), 4);
}

} // namespace
} // namespace curvetet

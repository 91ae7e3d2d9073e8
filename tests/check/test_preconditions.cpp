// One tiny mesh per defect class (InputDefect), each asserting the class is
// found with the right element ids, plus valid shapes that must pass.
#include "curvetet/check/preconditions.hpp"
#include "curvetet/check/self_intersection.hpp"
#include "support/shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace curvetet;
using namespace curvetet::test;
using check::check_preconditions;

namespace {

const check::Defect* find(const check::PreconditionReport& r, InputDefect kind) {
  for (const auto& d : r.defects)
    if (d.kind == kind) return &d;
  return nullptr;
}

check::PreconditionReport run(const SurfaceMesh& m) { return check_preconditions(mesh::to_soup(m)); }

} // namespace

TEST(Preconditions, ValidShapesPass) {
  for (const auto& m : {tetrahedron(), cube(), join(cube(), cube(2, 3))}) {
    auto r = run(m);
    EXPECT_TRUE(r.ok()) << r.text();
    EXPECT_EQ(r.exit_code(), 0);
  }
}

TEST(Preconditions, CavityFacingInwardIsValid) {
  // A cube with a cubic cavity: the cavity wall's normals point into the hole,
  // i.e. it is the flipped small cube.
  auto r = run(join(cube(0, 3), flipped(cube(1, 2))));
  EXPECT_TRUE(r.ok()) << r.text();
  EXPECT_EQ(r.num_components, 2u);
}

TEST(Preconditions, TinyButNonZeroTriangleIsValid) {
  auto m = tetrahedron();
  m.vertices[3] = Vec3(0.5, 0.5, 1e-30); // face (1,2,3) has area ~1e-30, not zero
  auto r = run(m);
  EXPECT_TRUE(r.ok()) << r.text();
  EXPECT_LT(r.min_relative_area, 1e-29);
}

TEST(Preconditions, EmptyIsUnreadable) {
  auto r = check_preconditions(mesh::PolygonSoup{});
  ASSERT_NE(find(r, InputDefect::unreadable), nullptr);
  EXPECT_EQ(r.exit_code(), exit_code(InputDefect::unreadable));
}

TEST(Preconditions, NonFiniteCoordinate) {
  auto m = tetrahedron();
  m.vertices[2].y() = std::numeric_limits<double>::quiet_NaN();
  m.vertices[3].z() = std::numeric_limits<double>::infinity();
  auto r = run(m);
  const auto* d = find(r, InputDefect::non_finite);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->count, 2u);
  EXPECT_EQ(d->examples[0][0], 2);
  EXPECT_EQ(d->examples[1][0], 3);
  EXPECT_EQ(r.exit_code(), exit_code(InputDefect::non_finite));
}

TEST(Preconditions, IndexOutOfRange) {
  auto soup = mesh::to_soup(tetrahedron());
  soup.polygons[3][1] = 7;
  soup.polygons[1][0] = -1;
  auto r = check_preconditions(soup);
  const auto* d = find(r, InputDefect::index_out_of_range);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->examples, (std::vector<std::vector<long long>>{{1}, {3}}));
}

TEST(Preconditions, NonTriangleFace) {
  auto soup = mesh::to_soup(cube());
  soup.polygons.push_back({0, 1, 3, 2});
  auto r = check_preconditions(soup);
  const auto* d = find(r, InputDefect::non_triangle);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->examples[0], (std::vector<long long>{12, 4}));
  EXPECT_EQ(r.exit_code(), exit_code(InputDefect::non_triangle));
}

TEST(Preconditions, DuplicateFace) {
  auto m = tetrahedron();
  m.faces.push_back({1, 0, 2}); // face 0 again, other orientation
  auto r = run(m);
  const auto* d = find(r, InputDefect::duplicate_face);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->examples[0], (std::vector<long long>{0, 4}));
  EXPECT_EQ(r.exit_code(), exit_code(InputDefect::duplicate_face));
}

TEST(Preconditions, ExactlyDegenerateTriangle) {
  //  2           a closed "tet" whose vertex 3 lies exactly on edge 1-2's line
  //  |\          makes faces (1,2,3) zero-area; the others keep their area.
  //  | 3
  //  |  \ .
  //  0---1
  auto m = tetrahedron();
  m.vertices[3] = Vec3(0.5, 0.5, 0); // midpoint of 1-2: collinear exactly
  auto r = run(m);
  const auto* d = find(r, InputDefect::degenerate_triangle);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->examples, (std::vector<std::vector<long long>>{{3}}));
  EXPECT_EQ(r.exit_code(), exit_code(InputDefect::degenerate_triangle));
}

TEST(Preconditions, CoincidentCornersAreDegenerate) {
  auto m = tetrahedron();
  m.vertices[3] = m.vertices[0];
  auto r = run(m);
  const auto* d = find(r, InputDefect::degenerate_triangle);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->count, 2u); // faces (0,1,3) and (0,3,2)
}

TEST(Preconditions, NonManifoldEdge) {
  // Three tets glued along edge (0,1): six faces meet there.
  SurfaceMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(-0.5, 0.8, 0), Vec3(-0.5, -0.8, 0)};
  m.faces = {{0, 1, 2}, {0, 3, 1}, {0, 1, 3}, {0, 4, 1}, {0, 1, 4}, {0, 2, 1}, {0, 3, 2}, {0, 4, 3}, {0, 2, 4},
             {1, 2, 3}, {1, 3, 4}, {1, 4, 2}};
  auto r = run(m);
  const auto* d = find(r, InputDefect::nonmanifold_edge);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->examples[0], (std::vector<long long>{0, 1}));
}

TEST(Preconditions, NonManifoldVertexBowTie) {
  //   two tets touching at one shared vertex (index 3 of the first = index 0
  //   of the second after welding): a bow-tie, every edge manifold.
  auto a = tetrahedron();
  auto b = tetrahedron(Vec3(0, 0, 1));
  auto m = join(a, b);
  // weld b's vertex 0 (index 4) onto a's vertex 3
  for (auto& f : m.faces)
    for (int& v : f)
      if (v == 4) v = 3;
  auto r = run(m);
  const auto* d = find(r, InputDefect::nonmanifold_vertex);
  ASSERT_NE(d, nullptr) << r.text();
  EXPECT_EQ(d->examples, (std::vector<std::vector<long long>>{{3}}));
  EXPECT_EQ(find(r, InputDefect::self_intersection), nullptr) << r.text();
  EXPECT_EQ(r.exit_code(), exit_code(InputDefect::nonmanifold_vertex));
}

TEST(Preconditions, OpenBoundary) {
  auto m = tetrahedron();
  m.faces.pop_back();
  auto r = run(m);
  const auto* d = find(r, InputDefect::open_boundary);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->count, 3u);
  EXPECT_EQ(r.exit_code(), exit_code(InputDefect::open_boundary));
}

TEST(Preconditions, InconsistentOrientation) {
  auto m = tetrahedron();
  std::swap(m.faces[0][1], m.faces[0][2]);
  auto r = run(m);
  const auto* d = find(r, InputDefect::inconsistent_orientation);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->count, 3u); // the three edges of the flipped face
  EXPECT_EQ(r.exit_code(), exit_code(InputDefect::inconsistent_orientation));
}

TEST(Preconditions, InvertedSolidIsWrongOrientation) {
  auto r = run(flipped(cube()));
  const auto* d = find(r, InputDefect::wrong_orientation);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->examples[0], (std::vector<long long>{0, 0}));
  EXPECT_EQ(r.exit_code(), exit_code(InputDefect::wrong_orientation));
}

TEST(Preconditions, CavityFacingOutwardIsWrongOrientation) {
  auto r = run(join(cube(0, 3), cube(1, 2)));
  const auto* d = find(r, InputDefect::wrong_orientation);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->examples[0], (std::vector<long long>{12, 1})); // inner cube, nested once
}

TEST(Preconditions, InterpenetratingComponentsSelfIntersect) {
  auto r = run(join(cube(0, 2), cube(1, 3)));
  const auto* d = find(r, InputDefect::self_intersection);
  ASSERT_NE(d, nullptr);
  EXPECT_GT(d->count, 0u);
  EXPECT_EQ(r.exit_code(), exit_code(InputDefect::self_intersection));
}

TEST(Preconditions, TouchingComponentsSelfIntersect) {
  // Two cubes sharing a face's position (distinct vertex ids) touch: invalid.
  auto r = run(join(cube(0, 1), cube(1, 2)));
  EXPECT_NE(find(r, InputDefect::self_intersection), nullptr);
}

TEST(SelfIntersection, AdjacentFacesRules) {
  SurfaceMesh m;
  //  shared edge 0-1 ; 2 and 3 on the same side in the same plane = overlap
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.5, 2, 0), Vec3(0.5, -1, 0), Vec3(0.5, 1, 1e-300)};
  m.faces = {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}, {1, 0, 5}};
  EXPECT_TRUE(check::faces_intersect(m, 0, 1));  // coplanar, same side: folded over
  EXPECT_FALSE(check::faces_intersect(m, 0, 2)); // coplanar, opposite sides: flat
  EXPECT_FALSE(check::faces_intersect(m, 0, 3)); // same side but off the plane by 1e-300
  // shared vertex 0 only: face (0,3',4') crossing face 0 away from vertex 0
  m.vertices.push_back(Vec3(0.2, 0.2, -1));
  m.vertices.push_back(Vec3(0.2, 0.2, 1));
  m.faces.push_back({0, 6, 7});
  EXPECT_TRUE(check::faces_intersect(m, 0, 4));
  m.vertices.push_back(Vec3(-1, -1, 1));
  m.faces.push_back({0, 7, 8});
  EXPECT_FALSE(check::faces_intersect(m, 0, 5)); // touches only at vertex 0
}

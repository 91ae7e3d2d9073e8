// tetrahedralize() end to end with the shell's one-sided extrusion: singular
// vertices (zero-length pillars), very thin parts, the exterior, and the CLI
// (the written .msh read back). Every case checks the exact contract: doubles,
// positive tets (exact orient3d), boundary = input triangles, interior faces
// shared by two tets, volume = enclosed volume.
#include "shapes.hpp"
#include "shell/tiny_meshes.hpp"

#include "curvetet/core/threads.hpp"
#include "curvetet/geometry/predicates.hpp"
#include "curvetet/io/msh.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/io/write_surface.hpp"
#include "curvetet/volume/tet_amips.hpp"
#include "curvetet/volume/tetrahedralize.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace curvetet {
namespace {

volume::TetrahedralizeResult expect_exact_by(const mesh::SurfaceMesh& s, bool exterior, bool direct) {
  volume::TetrahedralizeOptions o;
  o.exterior = exterior;
  o.direct = direct;
  auto r = volume::tetrahedralize(s, o);
  for (int v = 0; v < s.num_vertices(); ++v)
    EXPECT_EQ(std::memcmp(r.mesh.vertices[v].data(), s.vertices[v].data(), 3 * sizeof(double)), 0) << v;
  mesh::LinearTetMesh inside = r.mesh;
  inside.tets.clear();
  for (int t = 0; t < r.mesh.num_tets(); ++t)
    if (r.mesh.tags[t] == 1) inside.tets.push_back(r.mesh.tets[t]);
  const auto check = volume::verify_tet_mesh(inside, s.faces); // recomputed here, not trusted
  EXPECT_TRUE(check.ok()) << check.text();
  const double vol = test::enclosed_volume(s);
  EXPECT_NEAR(check.volume, vol, 1e-9 * std::abs(vol));
  return r;
}

// Both fills: the Delaunay fast path where it applies, and the layered one.
volume::TetrahedralizeResult expect_exact(const mesh::SurfaceMesh& s, bool exterior = false) {
  expect_exact_by(s, exterior, false);
  return expect_exact_by(s, exterior, true);
}

// Thin slab [0,1]^2 x [0,t]: the layer must be thinner than t/2.
mesh::SurfaceMesh slab(double t) {
  auto m = test::unit_cube();
  for (auto& v : m.vertices) v.z() *= t;
  return m;
}

// Triangular prism whose cross-section has a 0.01 rad angle: a sharp, thin
// wedge edge along x.
//        2
//       /|      cross-section in (y, z): 0 = (0,0), 1 = (1,0),
//      / |      2 = (1, 0.01); extruded along x from 0 to 1.
//     0--1
mesh::SurfaceMesh thin_wedge() {
  mesh::SurfaceMesh m;
  const double h = 0.01;
  for (double x : {0.0, 1.0}) {
    m.vertices.emplace_back(x, 0, 0);
    m.vertices.emplace_back(x, 1, 0);
    m.vertices.emplace_back(x, 1, h);
  }
  m.faces = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  return m;
}

// A needle: 8-sided double cone, radius 0.01, length 2 (thin and sharp).
mesh::SurfaceMesh needle() {
  mesh::SurfaceMesh m;
  const int k = 8;
  m.vertices.emplace_back(0, 0, 1);  // 0: tip
  m.vertices.emplace_back(0, 0, -1); // 1: other tip
  for (int i = 0; i < k; ++i) {
    const double a = 2 * M_PI * i / k;
    m.vertices.emplace_back(0.01 * std::cos(a), 0.01 * std::sin(a), 0);
  }
  for (int i = 0; i < k; ++i) {
    const int r0 = 2 + i, r1 = 2 + (i + 1) % k;
    m.faces.push_back({0, r0, r1});
    m.faces.push_back({1, r1, r0});
  }
  return m;
}

TEST(VolumeTetrahedralize, ThinNeedle) { expect_exact(needle()); }

// The origin of the folded star sees faces with normals +z and -z: no
// pillar direction exists, the extrusion pins it (zero-length pillar).
TEST(VolumeTetrahedralize, SingularFoldedStar) {
  expect_exact_by(shell::test::folded_star(), false, true);
  const auto r = expect_exact_by(shell::test::folded_star(), false, false); // the layered fill
  EXPECT_GE(r.singular_inward, 1); // the case this test is about
}

TEST(VolumeTetrahedralize, VeryThinSlab) { expect_exact(slab(1e-4)); }

TEST(VolumeTetrahedralize, SharpThinWedge) { expect_exact(thin_wedge()); }

TEST(VolumeTetrahedralize, NonConvexSphereWithDent) {
  auto m = test::icosphere(2);
  for (auto& v : m.vertices)
    if (v.z() > 0.8) v.z() = 1.6 - v.z(); // push the cap inward: a dent
  expect_exact(m);
}

// A real scan (spot): the worst-tet passes flip, remove edges and split
// edges or tets here (each a transaction of its own); the result must stay
// exact, and better than TetGen's on the same model (max AMIPS 28.8; the
// figures here are in highorder/quality.hpp's convention, 3x the fill's
// energy and 3x docs/tetrahedralize_vs_tetgen.md's table).
TEST(VolumeTetrahedralize, SpotStaysExactThroughWorstTetSplits) {
  const auto spot = mesh::to_surface_mesh(io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/spot.off"));
  const auto r = expect_exact_by(spot, false, false); // the layered fill
  EXPECT_FALSE(r.interior.direct);
  EXPECT_GT(r.interior.splits, 0u);
  EXPECT_GT(r.interior.flips, 0u);
  EXPECT_LT(r.interior.max_amips, 28.8);
  std::printf("spot: %d tets, %zu splits, %zu flips, max AMIPS %.3g\n", r.mesh.num_tets(), r.interior.splits,
              r.interior.flips, r.interior.max_amips);
}

// cheese_genus133 is the good model the direct fill cannot do (cavity pieces
// without a kernel point around its bubbles). Its layered fill recovers
// most offset triangles by flips and cuts in only the rest: faces that are
// offset triangles are labelled, cut ones found, and both must give an exact
// result, better than TetGen's (max AMIPS 3780). The extrusion ran beside
// the failed direct attempt; with one thread it runs after it, and the
// output must be the same.
TEST(VolumeTetrahedralize, CheeseTakesTheLayeredFillWithFewCuts) {
  const auto cheese = mesh::to_surface_mesh(
      io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/cheese_genus133.off"));
  const auto r = expect_exact_by(cheese, false, true);
  EXPECT_FALSE(r.interior.direct);
  EXPECT_GT(r.interior.bsp_cuts, 0u);
  EXPECT_LT(r.interior.bsp_cuts, cheese.faces.size() / 2); // 6227; 34447 without the flips
  EXPECT_LT(r.interior.max_amips, 3780.0);
  ThreadLimit one(1);
  const auto serial = volume::tetrahedralize(cheese);
  EXPECT_EQ(serial.mesh.vertices, r.mesh.vertices);
  EXPECT_EQ(serial.mesh.tets, r.mesh.tets);
  std::printf("cheese: %d tets, %zu cuts, max AMIPS %.4g\n", r.mesh.num_tets(), r.interior.bsp_cuts,
              r.interior.max_amips);
}

// Every triangle of knot2 is a face of the Delaunay tetrahedralization of
// its vertices: the fast path fills it with no layer and no BSP, then
// inserts Steiner points inside until its worst tet beats TetGen's.
TEST(VolumeTetrahedralize, DelaunayConformingSurfaceTakesTheDirectFill) {
  const auto knot = mesh::to_surface_mesh(
      io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/knot2_two_components.off"));
  const auto r = expect_exact(knot);
  EXPECT_TRUE(r.interior.direct);
  EXPECT_EQ(r.interior.bsp_cuts, 0u);
  EXPECT_GT(r.interior.splits, 0u);
  EXPECT_LT(r.interior.max_amips, 14.88); // TetGen -pYq's maximum on this model
  std::printf("knot2: %d tets, %zu insertions or splits, max AMIPS %.4g\n", r.mesh.num_tets(), r.interior.splits,
              r.interior.max_amips);
}

// On cad_freecad_MSOP_10 a thin wedge of the surface forces the tet T* =
// (2085, 239, 9568, 2111) into every mesh whose worst tet is no worse
// (bench/msop_max_amips_bound.py proves it): T*'s energy is the least
// maximum any tetrahedralization of this model can have, and ours has it.
TEST(VolumeTetrahedralize, MsopReachesTheLeastPossibleMaximum) {
  const auto msop = mesh::to_surface_mesh(
      io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/cad_freecad_MSOP_10.off"));
  const auto r = expect_exact_by(msop, false, true);
  const auto& x = msop.vertices;
  const double forced = std::min(volume::tet_amips(x[2085], x[239], x[9568], x[2111]),
                                 volume::tet_amips(x[2085], x[239], x[2111], x[9568]));
  EXPECT_LT(forced, 8.29); // the fill's energy (volume/tet_amips.hpp)
  EXPECT_LE(r.interior.max_amips, volume::kReportedAmipsPerEnergy * forced * (1 + 1e-12));
  std::printf("MSOP: %d tets, max AMIPS %.17g, forced tet %.17g\n", r.mesh.num_tets(), r.interior.max_amips, forced);
}

// 118 triangles of spot are not Delaunay faces, and some of their edges are
// not Delaunay edges either: edge removals and walks of 2-3 flips along the
// missing edges recover them all.
TEST(VolumeTetrahedralize, MissingDelaunayEdgesAreRecoveredByFlipWalks) {
  const auto spot = mesh::to_surface_mesh(io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/spot.off"));
  const auto r = expect_exact_by(spot, false, true);
  EXPECT_TRUE(r.interior.direct);
  EXPECT_LT(r.interior.max_amips, 28.8); // TetGen -pYq's maximum on this model
}

// Two triangles of cad_fillet3 are not Delaunay faces (co-circular points
// on a flat face): edge removals recover them, and the fast path applies;
// the flat tets between the two triangles of each fillet quad need
// Steiner points well inside (TetGen -pYq's maximum there: 20.01).
TEST(VolumeTetrahedralize, MissingDelaunayTrianglesAreRecoveredByEdgeRemoval) {
  const auto part = mesh::to_surface_mesh(io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/cad_fillet3.off"));
  const auto r = expect_exact_by(part, false, true);
  EXPECT_TRUE(r.interior.direct);
  EXPECT_LT(r.interior.max_amips, 20.01);
  std::printf("cad_fillet3: %d tets, max AMIPS %.4g\n", r.mesh.num_tets(), r.interior.max_amips);
}

// Schönhardt's twisted prism: its three lateral quads fold inward along
// their diagonals, so no tetrahedralization of its six vertices exists (each
// tet would have to use an outside diagonal). The Delaunay fill must stand a
// cone from an interior Steiner point in for what flips cannot recover.
mesh::SurfaceMesh schoenhardt() {
  mesh::SurfaceMesh m;
  const double twist = M_PI / 6;
  for (int i = 0; i < 3; ++i) m.vertices.emplace_back(std::cos(2 * M_PI * i / 3), std::sin(2 * M_PI * i / 3), 0);
  for (int i = 0; i < 3; ++i)
    m.vertices.emplace_back(std::cos(2 * M_PI * i / 3 + twist), std::sin(2 * M_PI * i / 3 + twist), 1);
  m.faces = {{0, 2, 1}, {3, 4, 5}};
  for (int i = 0; i < 3; ++i) {
    const int a = i, b = (i + 1) % 3, c = 3 + (i + 1) % 3, d = 3 + i; // quad a b c d, outward
    m.faces.push_back({a, b, c}); // diagonal a-c: with the top turned
    m.faces.push_back({a, c, d}); // forward, it folds inward
  }
  return m;
}

TEST(VolumeTetrahedralize, SchoenhardtPrismGetsAnInteriorSteinerPoint) {
  const auto prism = schoenhardt();
  // The folds: each quad bends inward along its diagonal (the far corner of
  // one triangle lies outside the other's plane), the case this test is about.
  for (int i = 0; i < 3; ++i) {
    const auto& f = prism.faces[2 + 2 * i];
    const auto& far = prism.vertices[prism.faces[3 + 2 * i][2]];
    EXPECT_GT(geometry::orient3d(prism.vertices[f[0]], prism.vertices[f[1]], prism.vertices[f[2]], far), 0);
  }
  const auto r = expect_exact(prism);
  EXPECT_TRUE(r.interior.direct);
  EXPECT_GT(r.interior.missing_triangles, r.interior.recovered_by_flips);
  EXPECT_GE(r.interior.cones, 1u);
}

// thingi10k_44901: beside a strip of needle triangles (area 4e-20) the
// solid is 1e-17 thick, so no Steiner point fits there and no cone closes
// (the cavity grows into a whole part without kernel point). Its cavity
// pieces are peeled instead (volume/peel_fill.hpp), with the surface's own
// vertices only, and the fill must be exact.
TEST(VolumeTetrahedralize, NeedleStripIsFilledByPeeling) {
  const auto part = mesh::to_surface_mesh(
      io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/thingi10k_44901.off"));
  const auto r = expect_exact_by(part, false, true);
  EXPECT_TRUE(r.interior.direct);
  EXPECT_GT(r.interior.missing_triangles, r.interior.recovered_by_flips);
}

// Some triangles of the bunny stay missing after the flips, inside and
// outside; the cones around them keep the fast path, which must still beat
// TetGen's worst tet (123).
TEST(VolumeTetrahedralize, ScanKeepsTheDirectFillThroughCones) {
  const auto bunny = mesh::to_surface_mesh(
      io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/bunny_libigl.off"));
  const auto r = expect_exact_by(bunny, /*exterior=*/true, true);
  EXPECT_TRUE(r.interior.direct);
  EXPECT_GE(r.interior.cones, 1u);
  EXPECT_LT(r.interior.max_amips, 123.0);
  // Outside too (offset points, box and grid points; cones of their own).
  EXPECT_TRUE(r.exterior.direct);
  EXPECT_GE(r.exterior.cones, 1u);
  EXPECT_TRUE(r.exterior_check.ok()) << r.exterior_check.text();
  std::printf("bunny: %zu of %zu missing triangles recovered by flips, %zu cones, max AMIPS %.4g\n",
              r.interior.recovered_by_flips, r.interior.missing_triangles, r.interior.cones, r.interior.max_amips);
}

// abc_00000001 has needle input faces (0.07 x 0.0008) under a free vertex
// 2e-5 deep and hemmed in by its star (max AMIPS 1.5e5 before relocation):
// it must move through a cavity, and the result must stay exact.
TEST(VolumeTetrahedralize, HemmedVertexRelocatesThroughACavity) {
  const auto abc = mesh::to_surface_mesh(
      io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/abc_00000001_forgescan.off"));
  expect_exact_by(abc, false, true);
  const auto r = expect_exact_by(abc, false, false); // the layered fill, where the vertex is
  EXPECT_GT(r.interior.relocations, 0u);
  EXPECT_LT(r.interior.max_amips, 2.562e4); // TetGen -pYq's maximum on this model
  std::printf("abc_00000001: %d tets, %zu relocations, max AMIPS %.4g\n", r.mesh.num_tets(), r.interior.relocations,
              r.interior.max_amips);
}

TEST(VolumeTetrahedralize, InteriorAndExteriorShareTheSurface) {
  const auto m = test::octahedron();
  const auto r = expect_exact(m, true);
  mesh::LinearTetMesh outside = r.mesh;
  outside.tets.clear();
  for (int t = 0; t < r.mesh.num_tets(); ++t)
    if (r.mesh.tags[t] == 2) outside.tets.push_back(r.mesh.tets[t]);
  ASSERT_FALSE(outside.tets.empty());
  std::vector<mesh::Tri> reversed;
  for (auto f : m.faces) reversed.push_back({f[0], f[2], f[1]});
  Eigen::Vector3d lo = r.mesh.vertices[0], hi = lo;
  for (const auto& p : r.mesh.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const auto check = volume::verify_tet_mesh(outside, reversed, volume::Box{lo, hi});
  EXPECT_TRUE(check.ok()) << check.text();
  const double box = (hi - lo).prod();
  EXPECT_NEAR(check.volume, box - test::enclosed_volume(m), 1e-9 * box);
  // the whole mesh: only the box is boundary
  const auto all = volume::verify_tet_mesh(r.mesh, {}, volume::Box{lo, hi});
  EXPECT_TRUE(all.ok()) << all.text();
}

mesh::LinearTetMesh read_back(const std::string& path) { return mesh::to_linear_mesh(io::read_msh(path)); }

TEST(VolumeTetrahedralize, CommandWritesAVerifiableMsh) {
  const auto dir = std::filesystem::temp_directory_path() / "curvetet_test_tetrahedralize";
  std::filesystem::create_directories(dir);
  const auto m = needle();
  io::write_surface((dir / "crown.off").string(), m);
  const auto out = (dir / "crown.msh").string();
  std::filesystem::remove(out);
  const std::string cmd = std::string(CURVETET_BINARY) + " -q tetrahedralize " + (dir / "crown.off").string() +
                          " -o " + out;
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const auto back = read_back(out);
  ASSERT_GE(back.num_vertices(), m.num_vertices());
  for (int v = 0; v < m.num_vertices(); ++v) EXPECT_EQ(back.vertices[v], m.vertices[v]) << v;
  const auto check = volume::verify_tet_mesh(back, m.faces);
  EXPECT_TRUE(check.ok()) << check.text();
  // Gmsh itself reads the file and finds the same tets.
  if (std::filesystem::exists("/usr/bin/python3")) {
    const auto count = (dir / "count.txt").string();
    const std::string py = "/usr/bin/python3 -c \"import gmsh; gmsh.initialize(); "
                           "gmsh.option.setNumber('General.Terminal', 0); gmsh.open('" + out + "'); "
                           "t, e, n = gmsh.model.mesh.getElements(3); "
                           "open('" + count + "', 'w').write(str(sum(len(x) for x in e)))\"";
    if (std::system(py.c_str()) == 0) {
      std::ifstream in(count);
      long n = -1;
      in >> n;
      EXPECT_EQ(n, back.num_tets());
    }
  }
}

// --layered keeps the paper's fill where the fast path would apply; the
// report says which fill ran.
TEST(VolumeTetrahedralize, LayeredFlagForcesTheLayeredFill) {
  const auto dir = std::filesystem::temp_directory_path() / "curvetet_test_tetrahedralize_layered";
  std::filesystem::create_directories(dir);
  const auto cube = test::unit_cube();
  io::write_surface((dir / "cube.off").string(), cube);
  for (const bool layered : {false, true}) {
    const auto out = (dir / "cube.msh").string(), report = (dir / "cube.json").string();
    const std::string cmd = std::string(CURVETET_BINARY) + " -q tetrahedralize " + (dir / "cube.off").string() +
                            " -o " + out + " --report " + report + (layered ? " --layered" : "");
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    std::ifstream in(report);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_NE(text.str().find(layered ? "\"direct\": false" : "\"direct\": true"), std::string::npos) << text.str();
    const auto check = volume::verify_tet_mesh(read_back(out), cube.faces);
    EXPECT_TRUE(check.ok()) << check.text();
  }
}

// The optimizer's rejections are counted by named reason: on a sphere its
// collapses and flips are turned down for energy and for no gain, and no
// reason is counted that the fill cannot meet (nothing is frozen but the
// surface, whose vertices are never proposed for removal).
TEST(VolumeTetrahedralize, OptimizerRejectionsAreCountedByReason) {
  const auto r = volume::tetrahedralize(test::icosphere(3));
  const auto& s = r.interior;
  const auto count = [&](volume::FillReject why) { return s.rejected[static_cast<int>(why)]; };
  EXPECT_GT(count(volume::FillReject::energy) + count(volume::FillReject::no_gain), 0u);
  EXPECT_GT(count(volume::FillReject::topology), 0u);
  EXPECT_EQ(count(volume::FillReject::sizing), 0u); // no sizing bound asked for
  const auto json = s.rejected_json();
  ASSERT_EQ(json.size(), static_cast<std::size_t>(volume::kFillRejectReasons));
  for (int i = 0; i < volume::kFillRejectReasons; ++i)
    EXPECT_TRUE(json.contains(volume::to_string(static_cast<volume::FillReject>(i)))) << i;
}

} // namespace
} // namespace curvetet

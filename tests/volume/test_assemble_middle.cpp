// The assembly on the middle surface (volume/assemble_middle.hpp): a fill of
// the surface S (each corner on the middle or retracted to the bottom), the
// slab tets of retracted pillars, boundary nodes on the curved patches;
// checked with the whole-mesh verifier (certified positivity, conformity,
// boundary = the middle surface).
#include "curvetet/check/verify_tet_mesh.hpp"
#include "curvetet/highorder/element_map.hpp"
#include "curvetet/highorder/node_ordering.hpp"
#include "curvetet/io/read_surface.hpp"
#include "curvetet/volume/assemble_middle.hpp"
#include "curvetet/volume/tetrahedralize.hpp"
#include "tet_shell.hpp"

#include <gtest/gtest.h>

using namespace curvetet;
using mesh::Vec3;
using test::tet_shell;

namespace {

mesh::TetMesh assemble(const volume::CurvedMiddle& s, const std::vector<char>& retracted, int order,
                       volume::AssemblyStats* stats) {
  const auto fill = volume::tetrahedralize(volume::retracted_surface(s, retracted));
  return volume::assemble_retracted(s, retracted, fill.mesh, order, stats);
}

// Largest distance of a boundary node of m from the middle patch of its face
// (boundary triangle f is shell face f), at the node's lattice point.
double off_patch(const mesh::TetMesh& m, const volume::CurvedMiddle& s) {
  double worst = 0;
  const int per = m.triangle_nodes();
  for (int f = 0; f < m.num_boundary(); ++f) {
    const int* ids = m.boundary_triangle(f);
    // Corner k of the boundary triangle is shell face f's corner r + k.
    int r = 0;
    while ((m.nodes[ids[0]] - s.middle_nodes[f][r]).norm() > 0) ++r;
    for (int i = 0; i < per; ++i) {
      const auto q = highorder::triangle_node(m.order, i);
      std::array<double, 3> local = {double(m.order - q[0] - q[1]) / m.order, double(q[0]) / m.order,
                                     double(q[1]) / m.order};
      std::array<double, 3> w{};
      for (int k = 0; k < 3; ++k) w[(r + k) % 3] = local[k];
      const Vec3 p = highorder::triangle_point(s.degree, s.middle_nodes[f].data(), Eigen::Vector2d(w[1], w[2]));
      worst = std::max(worst, (m.nodes[ids[i]] - p).norm());
    }
  }
  return worst;
}

} // namespace

TEST(AssembleMiddle, NothingRetractedFillsTheCurvedMiddleWithoutSlabs) {
  for (int order : {3, 4}) {
    const auto s = tet_shell(0.15, false);
    volume::AssemblyStats stats;
    const auto m = assemble(s, std::vector<char>(4, 0), order, &stats);
    EXPECT_EQ(stats.slab_tets, 0);
    EXPECT_EQ(m.num_tets(), stats.fill_tets);
    EXPECT_EQ(m.num_boundary(), 4);
    EXPECT_LT(off_patch(m, s), 1e-15);
    const auto v = check::verify_tet_mesh(m, {});
    EXPECT_TRUE(v.ok()) << v.text();
    EXPECT_EQ(v.positive, static_cast<std::size_t>(m.num_tets()));
  }
}

TEST(AssembleMiddle, EveryCornerRetractedIsThePapersAssembly) {
  const auto s = tet_shell(0.15, false);
  volume::AssemblyStats stats;
  const auto m = assemble(s, std::vector<char>(4, 1), 4, &stats);
  EXPECT_EQ(stats.slab_tets, 12); // 3 per face, as assemble_curved_mesh
  EXPECT_EQ(m.num_boundary(), 4);
  EXPECT_LT(off_patch(m, s), 1e-15);
  const auto v = check::verify_tet_mesh(m, {});
  EXPECT_TRUE(v.ok()) << v.text();
}

TEST(AssembleMiddle, ARetractedCornerKeepsOnlyTheSlabTetsOfItsPillar) {
  const auto s = tet_shell(0.15, false);
  volume::AssemblyStats stats;
  const auto m = assemble(s, {1, 0, 0, 0}, 3, &stats);
  EXPECT_EQ(stats.slab_tets, 3); // one in each face around corner 0
  EXPECT_LT(off_patch(m, s), 1e-15);
  const auto v = check::verify_tet_mesh(m, {});
  EXPECT_TRUE(v.ok()) << v.text();
}

TEST(AssembleMiddle, SingularCornerIsNeverRetracted) {
  const auto s = tet_shell(0.1, true); // vertex 0: bottom == middle
  volume::AssemblyStats stats;
  const auto m = assemble(s, std::vector<char>(4, 1), 3, &stats);
  EXPECT_EQ(stats.slab_tets, 9); // the 3 tets of pillar 0 have no volume
  const auto v = check::verify_tet_mesh(m, {});
  EXPECT_TRUE(v.ok()) << v.text();
}

// cheese_genus133's surface has no direct fill (cavity pieces without a
// kernel point around its bubbles): as a flat middle surface (every vertex
// pinched, so nothing retracts) it is filled by the layered fill instead of
// sending the job to the slab assembly.
TEST(AssembleMiddle, SurfaceWithoutDirectFillTakesTheLayeredFill) {
  const auto cheese = mesh::to_surface_mesh(
      io::read_surface(std::string(CURVETET_SHARED_DATA) + "/good/cheese_genus133.off"));
  volume::CurvedMiddle s;
  s.bottom = cheese.vertices;
  s.faces = cheese.faces;
  s.singular.assign(cheese.vertices.size(), 1);
  for (const auto& f : cheese.faces) s.middle_nodes.push_back({cheese.vertices[f[0]], cheese.vertices[f[1]], cheese.vertices[f[2]]});
  mesh::TetMesh m;
  nlohmann::json report;
  ASSERT_TRUE(volume::assemble_on_middle(s, 2, m, report)) << report.dump();
  EXPECT_EQ(report["layered_fill_rounds"], 1);
  EXPECT_EQ(report["slab_tets"], 0);
  EXPECT_EQ(m.num_boundary(), static_cast<int>(cheese.faces.size()));
  const auto v = check::verify_tet_mesh(m, {});
  EXPECT_TRUE(v.ok()) << v.text();
  EXPECT_EQ(v.positive, static_cast<std::size_t>(m.num_tets()));
}
